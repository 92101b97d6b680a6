/* Check case: still air (laminar, no flow), 1 ms steps, 0.1 s. */

#include "cs_defs.h"
#include "cs_domain.h"
#include "cs_parameters.h"
#include "cs_prototypes.h"
#include "cs_time_step.h"
#include "cs_turbulence_model.h"

BEGIN_C_DECLS

void
cs_user_model(void)
{
  cs_turb_model_t *turb_model = cs_get_glob_turb_model();
  turb_model->iturb = CS_TURB_NONE;
}

void
cs_user_parameters(cs_domain_t *domain)
{
  cs_time_step_options_t *time_opt = cs_get_glob_time_step_options();
  time_opt->idtvar = 0;
  domain->time_step->dt_ref = 1e-3;
  domain->time_step->nt_max = 100;
}

END_C_DECLS
