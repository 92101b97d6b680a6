/* Duct: no particles in the flow stage. In a particle run, one-way coupling, first-order
   scheme (depo's hook and Code_Saturne's deposition model both need it), turbulent
   dispersion from the k-epsilon field; Code_Saturne's deposition model (Guingo & Minier
   2008) on in the run "model" only. The model fixes each wall face's viscous length at the
   run's first Lagrangian step, from that step's friction velocity: a particle run restarts
   from the developed flow (run_duct.sh), so the model sees it. */

#include "cs_defs.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"

#include "duct.h"

BEGIN_C_DECLS

void
cs_user_lagr_model(void)
{
  if (duct_walls_mode() == DUCT_FLOW) {
    cs_glob_lagr_time_scheme->iilagr = CS_LAGR_OFF;
    return;
  }
  cs_glob_lagr_time_scheme->iilagr = CS_LAGR_ONEWAY_COUPLING;
  cs_glob_lagr_time_scheme->isuila = 0;
  cs_glob_lagr_time_scheme->isttio = 0;
  cs_glob_lagr_time_scheme->t_order = 1;
  cs_glob_lagr_time_scheme->idistu = 1;
  cs_glob_lagr_time_scheme->idiffl = 0;
  cs_glob_lagr_model->physical_model = 0;
  cs_glob_lagr_model->deposition = (duct_walls_mode() == DUCT_MODEL) ? 1 : 0;
}

END_C_DECLS
