/* Check case: 540 heavy spheres (1 mm, 8000 kg/m^3) placed at random in the box at the
   first step; cs_user_lagr_in (in depo_check_particles.c) then aims them at the floor. */

#include "cs_defs.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"
#include "cs_volume_zone.h"

BEGIN_C_DECLS

void
cs_user_lagr_volume_conditions(void)
{
  cs_lagr_zone_data_t *conditions = cs_lagr_get_volume_conditions();
  const cs_zone_t *all = cs_volume_zone_by_id(0);
  cs_lagr_injection_set_t *set = cs_lagr_get_injection_set(conditions, all->id, 0);
  set->n_inject = 540;
  set->injection_frequency = 0;
  set->velocity_profile = 1; /* imposed components (set per particle by cs_user_lagr_in) */
  set->velocity[0] = set->velocity[1] = set->velocity[2] = 0.0;
  set->stat_weight = 1.0;
  set->flow_rate = 0.0;
  set->diameter = 1e-3;
  set->diameter_variance = 0.0;
  set->density = 8000.0;
  set->temperature_profile = 0;
}

END_C_DECLS
