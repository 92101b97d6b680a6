/* Duct: k-epsilon turbulence, gravity along -z, 5 ms steps. The flow stage runs
   DUCT_FLOW_STEPS from rest; a particle run restarts from it for DUCT_PARTICLE_STEPS more
   (Code_Saturne's step count is absolute). The boundary field of the wall functions'
   friction velocity, `ustar`, is made in every run: the census reads it, depo's wall
   function reads it, and the deposition model would make it itself. */

#include "cs_defs.h"
#include "cs_domain.h"
#include "cs_field.h"
#include "cs_mesh_location.h"
#include "cs_parameters.h"
#include "cs_physical_constants.h"
#include "cs_prototypes.h"
#include "cs_time_step.h"
#include "cs_turbulence_model.h"

#include "duct.h"

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
  cs_time_step_options_t *time_opt = cs_get_glob_time_step_options();
  time_opt->idtvar = 0;
  domain->time_step->dt_ref = DUCT_DT;
  domain->time_step->nt_max = DUCT_FLOW_STEPS + (duct_walls_mode() == DUCT_FLOW ? 0 : DUCT_PARTICLE_STEPS);
  cs_physical_constants_t *constants = cs_get_glob_physical_constants();
  constants->gravity[0] = 0.0;
  constants->gravity[1] = 0.0;
  constants->gravity[2] = -9.81;
  /* The turbulence's initial state: k and epsilon of a 1 m/s flow in the 0.2 m duct. */
  cs_turb_ref_values_t *ref = cs_get_glob_turb_ref_values();
  ref->uref = 1.0;
  ref->almax = 0.2;
  cs_field_find_or_create("ustar", CS_FIELD_PROPERTY, CS_MESH_LOCATION_BOUNDARY_FACES, 1, false);
}

END_C_DECLS
