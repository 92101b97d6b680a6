/* Channel: what the run measures. At the last step of every stage, the flow in
   `channel_flow.csv` (the mean wall-function friction velocity of the wall faces, the bulk
   and centre-line velocities) and its profile across the channel in `channel_profile.csv`.
   At every step of a particle stage, the airborne particles of each class in
   `channel_counts.csv` (deposited particles leave the set, so a class's deposits in a step
   are the fall of its airborne count), with Code_Saturne's own count of the step's
   deposits and of particles lost by the tracking, for channel_report.py; and of each class,
   the particles in the wall cells (within one cell of either wall) and the sum of their
   speeds towards or away from the wall, |v_z|, for the report's free-flight check. Serial
   runs only. In the wall-function stage it first applies depo's wall function for the step
   (depo_cs_wall_function), and writes in the file's head the deposition velocity that depo's
   Wood gives each class at the walls' mean wall-function friction velocity at the first
   particle step (what the wall function then applies, the flow being developed). */

#include "cs_defs.h"

#include <math.h>
#include <stdio.h>

#include "bft_error.h"
#include "bft_printf.h"
#include "cs_domain.h"
#include "cs_field.h"
#include "cs_field_pointer.h"
#include "cs_lagr.h"
#include "cs_lagr_particle.h"
#include "cs_lagr_prototypes.h"
#include "cs_mesh.h"
#include "cs_mesh_quantities.h"
#include "cs_parall.h"
#include "cs_prototypes.h"
#include "cs_time_step.h"

#include "channel.h"
#ifdef CHANNEL_DEPO
#include "depo.h"
#include "depo_code_saturne.h"
#endif

BEGIN_C_DECLS

/* The area-weighted mean of the wall faces' friction velocity (all boundary faces are
   walls), or -1 without the field. */
static double
_mean_ustar(void)
{
  const cs_field_t *f = cs_field_by_name_try("ustar");
  if (f == NULL)
    return -1.0;
  const cs_real_t *area = cs_glob_mesh_quantities->b_face_surf;
  double sum = 0.0, total = 0.0;
  for (cs_lnum_t i = 0; i < cs_glob_mesh->n_b_faces; i++) {
    sum += area[i] * f->val[i];
    total += area[i];
  }
  return sum / total;
}

static void
_write_flow(void)
{
  const cs_mesh_t *m = cs_glob_mesh;
  const cs_real_t *vol = cs_glob_mesh_quantities->cell_vol;
  const cs_real_3_t *xc = (const cs_real_3_t *)cs_glob_mesh_quantities->cell_cen;
  const cs_real_3_t *u = (const cs_real_3_t *)CS_F_(vel)->val;
  const cs_real_t *k = CS_F_(k)->val;
  const cs_real_t *eps = CS_F_(eps)->val;

  /* The profile: cells binned by their centre's height (the mesh is uniform in z). */
  enum { NB = 64 };
  double zs[NB] = {0}, us[NB] = {0}, ks[NB] = {0}, es[NB] = {0}, vs[NB] = {0};
  double dz = 2.0 * CHANNEL_H_HALF;
  for (cs_lnum_t c = 0; c < m->n_cells; c++)
    if (xc[c][2] < dz)
      dz = xc[c][2];
  dz *= 2.0; /* the lowest centre is half a cell above the floor */
  double bulk = 0.0, volume = 0.0;
  for (cs_lnum_t c = 0; c < m->n_cells; c++) {
    int b = (int)floor(xc[c][2] / dz);
    if (b < 0 || b >= NB)
      continue;
    zs[b] += vol[c] * xc[c][2];
    us[b] += vol[c] * u[c][0];
    ks[b] += vol[c] * k[c];
    es[b] += vol[c] * eps[c];
    vs[b] += vol[c];
    bulk += vol[c] * u[c][0];
    volume += vol[c];
  }
  bulk /= volume;

  double ustar = _mean_ustar();
  double nu = CHANNEL_MU / CHANNEL_RHO;
  double centre = 0.0;
  FILE *f = fopen("channel_profile.csv", "w");
  fprintf(f, "z,u,k,epsilon\n");
  for (int b = 0; b < NB; b++) {
    if (vs[b] <= 0.0)
      continue;
    fprintf(f, "%.6e,%.6e,%.6e,%.6e\n", zs[b] / vs[b], us[b] / vs[b], ks[b] / vs[b], es[b] / vs[b]);
    if (us[b] / vs[b] > centre)
      centre = us[b] / vs[b];
  }
  fclose(f);

  f = fopen("channel_flow.csv", "w");
  fprintf(f, "step,ustar_imposed,ustar_wall_functions,bulk_velocity,centre_velocity,first_cell_yplus\n");
  fprintf(f, "%d,%.6f,%.6f,%.6f,%.6f,%.3f\n", cs_glob_time_step->nt_cur, CHANNEL_USTAR, ustar,
          bulk, centre, 0.5 * dz * (ustar > 0 ? ustar : CHANNEL_USTAR) / nu);
  fclose(f);
}

void
cs_user_extra_operations(cs_domain_t *domain)
{
  CS_UNUSED(domain);
  if (cs_glob_time_step->nt_cur == cs_glob_time_step->nt_max)
    _write_flow();
}

void
cs_user_lagr_extra_operations(const cs_real_t  dt[])
{
  CS_UNUSED(dt);
  if (cs_glob_n_ranks > 1)
    bft_error(__FILE__, __LINE__, 0, "channel: the census is written by serial runs only\n");
  const channel_run_t *run = channel_run();
  static FILE *f = NULL;
  int step = cs_glob_time_step->nt_cur - run->flow_steps;
#ifdef CHANNEL_DEPO
  if (run->stage == CHANNEL_WALL_FUNCTION)
    depo_cs_wall_function();
#endif
  if (f == NULL) {
    f = fopen("channel_counts.csv", "w");
    fprintf(f, "# stage %s, %ld particles per class, step %g s, ustar at the first particle step %.6f m/s\n",
            run->stage == CHANNEL_MODEL ? "guingo-minier"
            : run->stage == CHANNEL_WALL_FUNCTION ? "depo-wall-function" : "no-model",
            run->particles,
            run->particle_dt, _mean_ustar());
    fprintf(f, "# wall area %.9g m^2, volume %.9g m^3, wall cells' volume %.9g m^3\n",
            2.0 * CHANNEL_LX * CHANNEL_LY, 2.0 * CHANNEL_H_HALF * CHANNEL_LX * CHANNEL_LY,
            2.0 * (2.0 * CHANNEL_H_HALF / CHANNEL_NZ) * CHANNEL_LX * CHANNEL_LY);
    fprintf(f, "step,time");
    for (int c = 0; c < CHANNEL_CLASSES; c++)
      fprintf(f, ",airborne_%g", channel_tau_plus[c]);
    for (int c = 0; c < CHANNEL_CLASSES; c++)
      fprintf(f, ",near_%g", channel_tau_plus[c]);
    for (int c = 0; c < CHANNEL_CLASSES; c++)
      fprintf(f, ",abs_vz_%g", channel_tau_plus[c]);
    fprintf(f, ",deposited,failed\n");
    fprintf(f, "# diameters");
    for (int c = 0; c < CHANNEL_CLASSES; c++)
      fprintf(f, " %.6e", channel_diameter(c));
    fprintf(f, "\n");
#ifdef CHANNEL_DEPO
    if (run->stage == CHANNEL_WALL_FUNCTION) {
      DepoAir air = {CHANNEL_T, 101325.0, CHANNEL_RHO, CHANNEL_MU};
      double u[CHANNEL_CLASSES], d[CHANNEL_CLASSES], rho[CHANNEL_CLASSES], vd[CHANNEL_CLASSES];
      for (int c = 0; c < CHANNEL_CLASSES; c++) {
        u[c] = _mean_ustar();
        d[c] = channel_diameter(c);
        rho[c] = CHANNEL_DENSITY;
      }
      if (depo_deposition_velocity(DEPO_CORRELATION_WOOD, DEPO_SURFACE_WALL, &air, 0.0,
                                   CHANNEL_CLASSES, u, d, rho, vd) != DEPO_OK)
        bft_error(__FILE__, __LINE__, 0, "channel: %s\n", depo_last_error());
      fprintf(f, "# wall function v_d");
      for (int c = 0; c < CHANNEL_CLASSES; c++)
        fprintf(f, " %.6e", vd[c]);
      fprintf(f, "\n");
    }
#endif
  }

  long airborne[CHANNEL_CLASSES] = {0}, near[CHANNEL_CLASSES] = {0};
  double abs_vz[CHANNEL_CLASSES] = {0};
  const double cell = 2.0 * CHANNEL_H_HALF / CHANNEL_NZ;
  cs_lagr_particle_set_t *p = cs_glob_lagr_particle_set;
  for (cs_lnum_t i = 0; i < p->n_particles; i++) {
    double d = cs_lagr_particles_get_real(p, i, CS_LAGR_DIAMETER);
    int c = 0;
    while (c < CHANNEL_CLASSES - 1 && fabs(d - channel_diameter(c)) > 1e-6 * d)
      c++;
    airborne[c] += 1;
    const cs_real_t *x = cs_lagr_particles_attr_const(p, i, CS_LAGR_COORDS);
    if (x[2] < cell || x[2] > 2.0 * CHANNEL_H_HALF - cell) {
      const cs_real_t *v = cs_lagr_particles_attr_const(p, i, CS_LAGR_VELOCITY);
      near[c] += 1;
      abs_vz[c] += fabs(v[2]);
    }
  }
  fprintf(f, "%d,%.6e", step, step * run->particle_dt);
  for (int c = 0; c < CHANNEL_CLASSES; c++)
    fprintf(f, ",%ld", airborne[c]);
  for (int c = 0; c < CHANNEL_CLASSES; c++)
    fprintf(f, ",%ld", near[c]);
  for (int c = 0; c < CHANNEL_CLASSES; c++)
    fprintf(f, ",%.6e", abs_vz[c]);
  fprintf(f, ",%ld,%ld\n", (long)p->n_part_dep, (long)p->n_failed_part);
  if (cs_glob_time_step->nt_cur == cs_glob_time_step->nt_max) {
    fclose(f);
    f = NULL;
  }
}

END_C_DECLS
