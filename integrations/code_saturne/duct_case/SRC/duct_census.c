/* Duct: in every run, every 20 steps (0.1 s), each wall's area-weighted mean friction
   velocity (the boundary field `ustar`) and the largest streamwise velocity of the outlet's
   cells (the centre line's), in `duct_flow.csv`: how the flow stage develops and that a particle run's flow
   stays as it was. At the last step of a particle run, where each injected particle is:
   deposited on which wall, still in the air, or gone through the outlet (what was injected
   and is neither), and of those still in the air, how many are in a wall cell (within the
   first 0.05 m cell of a wall) and within 1 mm of a wall. Written to `duct_census.csv`, one
   row per size, for duct_report.py; with
   depo's walls, the contacts and the time per call of the law written to the log. Serial
   runs only.

   With depo's wall function (walls "wall-function"), at every step: before the hook draws,
   the chance that each particle in a wall cell deposits in the step, 1 - prod(1 - P_f) over
   its cell's wall faces f, with P_f from depo_wall_function_probability at the face's `ustar`
   and the cell's extent normal to the face taken here from the duct's geometry (its own
   route to the hook's inputs); summed per size, it is the number of deposits the
   correlation's flux v_d C_w predicts from the wall cells' particles, and the sum of
   q (1 - q) its binomial variance. Then depo_cs_wall_function() draws, and the fall of each
   size's count over that call is its deposits. The particle-steps spent in each class of wall
   cell and in the whole duct give the wall cells' concentration over the duct's, and at the
   last step each wall's area-weighted mean `ustar` and the correlation's velocity there, for
   the well-mixed prediction of duct_report.py. */

#include "cs_defs.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bft_error.h"
#include "cs_boundary_zone.h"
#include "cs_domain.h"
#include "cs_field.h"
#include "cs_field_pointer.h"
#include "cs_lagr.h"
#include "cs_lagr_particle.h"
#include "cs_lagr_prototypes.h"
#include "cs_mesh.h"
#include "cs_mesh_quantities.h"
#include "cs_parall.h"
#include "cs_physical_constants.h"
#include "cs_prototypes.h"
#include "cs_time_step.h"

#include "bft_printf.h"
#include "depo.h"
#include "depo_code_saturne.h"
#include "duct.h"

BEGIN_C_DECLS

/* The wall function's classes of wall: their zones and orientations. */
static const char *wf_walls[3] = {"floor", "ceiling", "sides"};
static const int32_t wf_orientation[3] = {DEPO_SURFACE_FLOOR, DEPO_SURFACE_CEILING, DEPO_SURFACE_WALL};

/* Per size: the predicted deposits, their variance, the deposits drawn, the particle-steps
   in the duct and in each class of wall cell. */
static double wf_expected[DUCT_SIZES], wf_variance[DUCT_SIZES];
static long wf_deposited[DUCT_SIZES];
static double wf_steps[DUCT_SIZES], wf_wall_steps[DUCT_SIZES][3];

static int
_size_of(double d)
{
  int s = 0;
  while (s < DUCT_SIZES - 1 && fabs(d - duct_diameters[s]) > 1e-3 * duct_diameters[s])
    s++;
  return s;
}

/* Each size's particles in a cell of the mesh. */
static void
_count_sizes(long n[DUCT_SIZES])
{
  const cs_lagr_particle_set_t *p = cs_glob_lagr_particle_set;
  for (int s = 0; s < DUCT_SIZES; s++)
    n[s] = 0;
  for (cs_lnum_t i = 0; i < p->n_particles; i++) {
    cs_lnum_t c = cs_lagr_particles_get_lnum(p, i, CS_LAGR_CELL_ID);
    if (c >= 0 && c < cs_glob_mesh->n_cells)
      n[_size_of(cs_lagr_particles_get_real(p, i, CS_LAGR_DIAMETER))] += 1;
  }
}

/* One step of the wall function: the prediction from the wall cells, the hook's draws. */
static void
_wall_function_step(void)
{
  const cs_mesh_t *m = cs_glob_mesh;
  const cs_mesh_quantities_t *q = cs_glob_mesh_quantities;
  const cs_lagr_particle_set_t *p = cs_glob_lagr_particle_set;
  const cs_field_t *ustar = cs_field_by_name("ustar");
  const cs_fluid_properties_t *fluid = cs_glob_fluid_properties;
  const cs_real_t *g = cs_glob_physical_constants->gravity;
  DepoAir air = {fluid->t0, fluid->p0, fluid->ro0, fluid->viscl0};
  double gravity = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  double dt = cs_glob_lagr_time_step->dtp;

  /* Each cell's wall faces (at most two in this duct: a corner) and their classes. */
  cs_lnum_t *faces = malloc(2 * m->n_cells * sizeof(cs_lnum_t));
  int *class = malloc(2 * m->n_cells * sizeof(int));
  for (cs_lnum_t c = 0; c < 2 * m->n_cells; c++)
    faces[c] = -1;
  for (int k = 0; k < 3; k++) {
    const cs_zone_t *z = cs_boundary_zone_by_name(wf_walls[k]);
    for (cs_lnum_t j = 0; j < z->n_elts; j++) {
      cs_lnum_t f = z->elt_ids[j], c = m->b_face_cells[f];
      int slot = faces[2 * c] < 0 ? 0 : 1;
      if (faces[2 * c + slot] >= 0)
        bft_error(__FILE__, __LINE__, 0, "duct: a cell with more than two wall faces\n");
      faces[2 * c + slot] = f;
      class[2 * c + slot] = k;
    }
  }
  for (cs_lnum_t i = 0; i < p->n_particles; i++) {
    cs_lnum_t c = cs_lagr_particles_get_lnum(p, i, CS_LAGR_CELL_ID);
    if (c < 0 || c >= m->n_cells)
      continue;
    double d = cs_lagr_particles_get_real(p, i, CS_LAGR_DIAMETER);
    double mass = cs_lagr_particles_get_real(p, i, CS_LAGR_MASS);
    double rho = mass / (3.14159265358979323846 / 6.0 * d * d * d);
    int s = _size_of(d);
    wf_steps[s] += 1.0;
    double stay = 1.0;
    for (int slot = 0; slot < 2; slot++) {
      cs_lnum_t f = faces[2 * c + slot];
      if (f < 0)
        continue;
      int k = class[2 * c + slot];
      /* The cell's extent normal to the face: the floor and ceiling are planes z = const,
         the sides y = const. */
      int axis = k == 2 ? 1 : 2;
      double layer = 2.0 * fabs(q->cell_cen[3 * c + axis] - q->b_face_cog[3 * f + axis]);
      double u = ustar->val[f], chance = 0.0;
      if (depo_wall_function_probability(DEPO_CORRELATION_LAI_NAZAROFF, wf_orientation[k], &air,
                                         gravity, dt, 1, &u, &layer, &d, &rho, &chance) != DEPO_OK)
        bft_error(__FILE__, __LINE__, 0, "duct: %s\n", depo_last_error());
      stay *= 1.0 - chance;
      wf_wall_steps[s][k] += 1.0;
    }
    wf_expected[s] += 1.0 - stay;
    wf_variance[s] += (1.0 - stay) * stay;
  }
  free(faces);
  free(class);

  long before[DUCT_SIZES], after[DUCT_SIZES];
  _count_sizes(before);
  depo_cs_wall_function();
  _count_sizes(after);
  for (int s = 0; s < DUCT_SIZES; s++)
    wf_deposited[s] += before[s] - after[s];
}

/* Per class of wall: the area-weighted mean `ustar`, and the volume of its wall cells. */
static void
_wall_means(double ustar_mean[3], double volume[3])
{
  const cs_mesh_t *m = cs_glob_mesh;
  const cs_mesh_quantities_t *q = cs_glob_mesh_quantities;
  const cs_field_t *ustar = cs_field_by_name("ustar");
  for (int k = 0; k < 3; k++) {
    const cs_zone_t *z = cs_boundary_zone_by_name(wf_walls[k]);
    double area = 0.0, sum = 0.0;
    volume[k] = 0.0;
    for (cs_lnum_t j = 0; j < z->n_elts; j++) {
      cs_lnum_t f = z->elt_ids[j];
      area += q->b_face_surf[f];
      sum += q->b_face_surf[f] * ustar->val[f];
      volume[k] += q->cell_vol[m->b_face_cells[f]];
    }
    ustar_mean[k] = sum / area;
  }
}

void
cs_user_extra_operations(cs_domain_t *domain)
{
  CS_UNUSED(domain);
  int step = cs_glob_time_step->nt_cur;
  if (step % 20 != 0 && step != cs_glob_time_step->nt_prev + 1)
    return;
  static FILE *f = NULL;
  if (f == NULL) {
    f = fopen("duct_flow.csv", "w");
    fprintf(f, "step,time,floor_ustar,ceiling_ustar,sides_ustar,outlet_centre_velocity\n");
  }
  double ustar_mean[3], volume[3];
  _wall_means(ustar_mean, volume);
  /* The outlet's cells: the largest of their velocities along the duct. */
  const cs_mesh_t *m = cs_glob_mesh;
  const cs_real_3_t *u = (const cs_real_3_t *)CS_F_(vel)->val;
  const cs_zone_t *z = cs_boundary_zone_by_name("outlet");
  double centre = 0.0;
  for (cs_lnum_t j = 0; j < z->n_elts; j++)
    centre = fmax(centre, u[m->b_face_cells[z->elt_ids[j]]][0]);
  fprintf(f, "%d,%.4f,%.6g,%.6g,%.6g,%.6g\n", step, cs_glob_time_step->t_cur, ustar_mean[0],
          ustar_mean[1], ustar_mean[2], centre);
  fflush(f);
  if (step == cs_glob_time_step->nt_max) {
    fclose(f);
    f = NULL;
  }
}

void
cs_user_lagr_extra_operations(const cs_real_t  dt[])
{
  CS_UNUSED(dt);
  if (duct_walls_mode() == DUCT_WALL_FUNCTION)
    _wall_function_step();
  if (cs_glob_time_step->nt_cur != cs_glob_time_step->nt_max)
    return;
  if (cs_glob_n_ranks > 1)
    bft_error(__FILE__, __LINE__, 0, "duct: the census is written by serial runs only\n");

  /* Per size: floor, ceiling, sides, airborne; airborne in a wall cell, within 1 mm of a wall. */
  long counts[DUCT_SIZES][4] = {{0}}, near[DUCT_SIZES][2] = {{0}};
  cs_lagr_particle_set_t *p = cs_glob_lagr_particle_set;
  for (cs_lnum_t i = 0; i < p->n_particles; i++) {
    double d = cs_lagr_particles_get_real(p, i, CS_LAGR_DIAMETER);
    int s = _size_of(d);
    const cs_real_t *x = cs_lagr_particles_attr_const(p, i, CS_LAGR_COORDS);
    int where = 3;
    /* The nearest wall of the 0.2 m x 0.2 m section. */
    double floor = x[2], ceiling = 0.2 - x[2], side = fmin(x[1], 0.2 - x[1]);
    if (cs_lagr_particles_get_flag(p, i, CS_LAGR_PART_DEPOSITED))
      where = (floor <= ceiling && floor <= side) ? 0 : (ceiling <= side ? 1 : 2);
    else {
      double gap = fmin(floor, fmin(ceiling, side));
      near[s][0] += gap < 0.05;
      near[s][1] += gap < 1e-3;
    }
    counts[s][where] += 1;
  }
  long injected = (long)DUCT_PER_STEP * (DUCT_LAST_STEP - DUCT_FIRST_STEP + 1);
  FILE *f = fopen("duct_census.csv", "w");
  fprintf(f, "walls,diameter,injected,floor,ceiling,sides,airborne,outlet,"
             "airborne_wall_cells,airborne_within_1mm\n");
  const char *mode[4] = {"sink", "depo", "wall-function", "model"};
  for (int s = 0; s < DUCT_SIZES; s++) {
    /* The wall function's deposits have left the set: not in the outlet's share. */
    long out = injected - counts[s][0] - counts[s][1] - counts[s][2] - counts[s][3] - wf_deposited[s];
    fprintf(f, "%s,%g,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld\n", mode[duct_walls_mode()],
            duct_diameters[s], injected, counts[s][0], counts[s][1], counts[s][2],
            counts[s][3], out, near[s][0], near[s][1]);
  }
  fclose(f);

  if (duct_walls_mode() == DUCT_WALL_FUNCTION) {
    /* Per size: the deposits, their prediction and its variance; per wall, the wall cells'
       concentration over the duct's, the mean ustar and the correlation's velocity there. */
    const cs_fluid_properties_t *fluid = cs_glob_fluid_properties;
    const cs_real_t *g = cs_glob_physical_constants->gravity;
    DepoAir air = {fluid->t0, fluid->p0, fluid->ro0, fluid->viscl0};
    double gravity = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    double ustar_mean[3], volume[3], duct_volume = 0.0;
    _wall_means(ustar_mean, volume);
    for (cs_lnum_t c = 0; c < cs_glob_mesh->n_cells; c++)
      duct_volume += cs_glob_mesh_quantities->cell_vol[c];
    f = fopen("duct_wall_function.csv", "w");
    fprintf(f, "diameter,injected,deposited,expected,expected_variance,"
               "floor_ustar,ceiling_ustar,sides_ustar,floor_vd,ceiling_vd,sides_vd,"
               "floor_near_ratio,ceiling_near_ratio,sides_near_ratio\n");
    for (int s = 0; s < DUCT_SIZES; s++) {
      double v[3], rho = DUCT_DENSITY, d = duct_diameters[s];
      for (int k = 0; k < 3; k++)
        if (depo_deposition_velocity(DEPO_CORRELATION_LAI_NAZAROFF, wf_orientation[k], &air,
                                     gravity, 1, &ustar_mean[k], &d, &rho, &v[k]) != DEPO_OK)
          bft_error(__FILE__, __LINE__, 0, "duct: %s\n", depo_last_error());
      fprintf(f, "%g,%ld,%ld,%.6g,%.6g", d, injected, wf_deposited[s], wf_expected[s],
              wf_variance[s]);
      for (int k = 0; k < 3; k++)
        fprintf(f, ",%.6g", ustar_mean[k]);
      for (int k = 0; k < 3; k++)
        fprintf(f, ",%.6g", v[k]);
      for (int k = 0; k < 3; k++)
        fprintf(f, ",%.6g", wf_steps[s] > 0 ? (wf_wall_steps[s][k] / volume[k])
                                                  / (wf_steps[s] / duct_volume) : 0.0);
      fprintf(f, "\n");
    }
    fclose(f);
  }

  if (duct_walls_mode() == DUCT_DEPO) {
    unsigned long long n[4];
    depo_cs_counts(n);
    unsigned long long calls = n[0] + n[1] + n[2] + n[3];
    bft_printf("depo: %llu contacts (%llu rebound, %llu captured, %llu skipped, %llu invalid), "
               "%.0f ns per call of depo_apply_f64\n",
               calls, n[0], n[1], n[2], n[3], 1e9 * depo_cs_apply_time() / (double)(calls ? calls : 1));
  }
}

END_C_DECLS
