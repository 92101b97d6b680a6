/* Channel: no particles in the flow stage; in a particle stage, one-way coupling, the
   first-order scheme (the deposition model has no other), Code_Saturne's turbulent
   dispersion from the k-epsilon field (idistu = 1, with the crossing-trajectory effect),
   and its deposition model (Guingo & Minier 2008) on or off. Brownian motion is left off
   in the bulk Langevin model (lamvbr = 0, the default): the deposition model carries its
   own Brownian term in the near-wall zone, and without the model it is negligible at
   these sizes (Wood's diffusion term is below 1e-5 at tau+ >= 0.1). In the wall-function
   stage the model is off and depo's wall function deposits the particles of the wall cells. */

#include "cs_defs.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"

#include "channel.h"

BEGIN_C_DECLS

void
cs_user_lagr_model(void)
{
  const channel_run_t *run = channel_run();
  if (run->stage == CHANNEL_FLOW) {
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
  cs_glob_lagr_brownian->lamvbr = 0;
  cs_glob_lagr_model->deposition = (run->stage == CHANNEL_MODEL) ? 1 : 0;
}

END_C_DECLS
