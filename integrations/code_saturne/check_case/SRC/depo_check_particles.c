/* Check case: each injected particle is lowered to 1 mm above the floor (the box is one cell
   high, so it stays in its cell) and aimed at the floor with one of 6 speeds and 3 angles from
   the normal, in turn, so that every combination meets the floor within the run. */

#include "cs_defs.h"

#include <math.h>

#include "cs_lagr.h"
#include "cs_lagr_particle.h"
#include "cs_lagr_prototypes.h"

BEGIN_C_DECLS

void
cs_user_lagr_in(cs_lagr_particle_set_t         *particles,
                const cs_lagr_injection_set_t  *zis,
                const cs_lnum_t                 particle_range[2],
                const cs_lnum_t                 particle_face_id[],
                const cs_real_t                 visc_length[])
{
  CS_UNUSED(zis);
  CS_UNUSED(particle_face_id);
  CS_UNUSED(visc_length);
  const double speeds[6] = {0.02, 0.05, 0.1, 0.5, 2.0, 5.0}; /* m/s */
  const double angles[3] = {0.0, 30.0, 60.0};                /* degrees from the normal */
  for (cs_lnum_t p_id = particle_range[0]; p_id < particle_range[1]; p_id++) {
    cs_lnum_t i = p_id - particle_range[0];
    double s = speeds[i % 6], a = angles[(i / 6) % 3] * acos(-1.0) / 180.0;
    cs_real_t *x = cs_lagr_particles_attr(particles, p_id, CS_LAGR_COORDS);
    x[2] = 1e-3;
    cs_real_t *v = cs_lagr_particles_attr(particles, p_id, CS_LAGR_VELOCITY);
    cs_real_t *seen = cs_lagr_particles_attr(particles, p_id, CS_LAGR_VELOCITY_SEEN);
    v[0] = s * sin(a);
    v[1] = 0.0;
    v[2] = -s * cos(a);
    seen[0] = seen[1] = seen[2] = 0.0;
  }
}

END_C_DECLS
