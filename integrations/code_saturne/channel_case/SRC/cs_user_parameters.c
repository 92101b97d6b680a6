/* Channel: standard air, k-epsilon with Code_Saturne's default wall functions, no gravity
   (Wood's correlation is for flow along a vertical wall or without gravity). The flow
   stage runs from a plug flow at CHANNEL_DT_FLOW; a particle stage restarts from it at
   its particle_dt. */

#include "cs_defs.h"
#include "cs_domain.h"
#include "cs_field.h"
#include "cs_lagr.h"
#include "cs_log.h"
#include "cs_mesh_location.h"
#include "cs_parameters.h"
#include "cs_physical_constants.h"
#include "cs_prototypes.h"
#include "cs_time_step.h"
#include "cs_turbulence_model.h"

#include "channel.h"

BEGIN_C_DECLS

void
cs_user_model(void)
{
  cs_turb_model_t *turb_model = cs_get_glob_turb_model();
  turb_model->iturb = CS_TURB_K_EPSILON;
}

void
cs_user_parameters(cs_domain_t *domain)
{
  const channel_run_t *run = channel_run();
  cs_time_step_options_t *time_opt = cs_get_glob_time_step_options();
  time_opt->idtvar = 0;
  if (run->stage == CHANNEL_FLOW) {
    domain->time_step->dt_ref = CHANNEL_DT_FLOW;
    domain->time_step->nt_max = run->flow_steps;
  }
  else {
    domain->time_step->dt_ref = run->particle_dt;
    domain->time_step->nt_max = run->flow_steps + run->particle_steps;
  }

  cs_glob_log_frequency = 100;
  cs_glob_lagr_log_frequency_n = 100;

  cs_fluid_properties_t *fluid = cs_get_glob_fluid_properties();
  fluid->ro0 = CHANNEL_RHO;
  fluid->viscl0 = CHANNEL_MU;
  fluid->t0 = CHANNEL_T;

  cs_physical_constants_t *constants = cs_get_glob_physical_constants();
  constants->gravity[0] = 0.0;
  constants->gravity[1] = 0.0;
  constants->gravity[2] = 0.0;

  /* Initial turbulence: of a 6 m/s flow with a mixing length scale of the half-height. */
  cs_turb_ref_values_t *ref = cs_get_glob_turb_ref_values();
  ref->uref = 6.0;
  ref->almax = CHANNEL_H_HALF;

  /* The wall-function friction velocity of each wall face, which Code_Saturne fills when
     the field exists (the deposition model makes it too): read by channel_census.c. */
  cs_field_find_or_create("ustar", CS_FIELD_PROPERTY, CS_MESH_LOCATION_BOUNDARY_FACES, 1, false);
}

END_C_DECLS
