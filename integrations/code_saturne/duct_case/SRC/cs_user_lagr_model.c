/* Duct: one-way coupling, first-order scheme (depo's hook needs it), turbulent dispersion
   from the k-epsilon field. */

#include "cs_defs.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"

BEGIN_C_DECLS

void
cs_user_lagr_model(void)
{
  cs_glob_lagr_time_scheme->iilagr = CS_LAGR_ONEWAY_COUPLING;
  cs_glob_lagr_time_scheme->isuila = 0;
  cs_glob_lagr_time_scheme->isttio = 0;
  cs_glob_lagr_time_scheme->t_order = 1;
  cs_glob_lagr_time_scheme->idistu = 1;
  cs_glob_lagr_time_scheme->idiffl = 0;
  cs_glob_lagr_model->physical_model = 0;
  cs_glob_lagr_model->deposition = 0;
}

END_C_DECLS
