/* depo inside Code_Saturne (6.0): the Brach & Dunn (1998) rebound/capture law of libdepo at
   every particle-wall contact of a boundary zone of type CS_LAGR_BC_USER.

   It needs Code_Saturne's first-order Lagrangian time scheme (t_order = 1, set in
   cs_user_lagr_model()): the second-order scheme's correction step recomputes the velocity from
   the values before the contact and would undo the rebound. depo_cs_setup() stops the run
   otherwise.

   Code_Saturne calls cs_lagr_user_boundary_interaction() once per contact, for one particle,
   with the particle moved to the end of its step (outside the domain), the face's outward unit
   normal and the point where the trajectory crossed the face. This file:

   - turns the face's unit normal into depo's normal into the fluid (the one pointing towards
     the centre of the face's cell);
   - applies the zone's law to the particle's velocity (`depo_apply_f64` on a batch of one);
   - REBOUND: the particle is put back at the crossing point (nudged one millionth of the way
     towards its cell's centre), with the rebound velocity, the normal component of the fluid
     velocity seen reflected as Code_Saturne's own rebound does, and is done for this step
     (CS_LAGR_PART_TREATED). The rest of the step after the contact is not tracked: a time error
     of at most one step per contact, as small as the step is;
   - CAPTURED: the particle is deposited as Code_Saturne's CS_LAGR_DEPO1 deposits it (flag
     CS_LAGR_PART_DEPOSITED, coordinates at the crossing point, removed from the flow, counted
     in the particle set's deposited number and weight and as a deposition event for the
     boundary statistics), or with `captured keep` as CS_LAGR_DEPO2 does (at rest on the wall
     inside its cell, state CS_LAGR_PART_STUCK, kept in memory);
   - SKIPPED: the step's displacement crossed the face, but the velocity at the end of the
     step points away from the wall (turbulent dispersion or drag turned it): no impact; the
     particle is put back at the contact point with its velocity unchanged, as for a rebound;
   - INVALID (a non-finite velocity): the particle leaves the domain (CS_EVENT_OUTFLOW).

   Each contact can also be written to `depo_impacts.csv` (rank 0 of a serial run, or one file
   per rank `depo_impacts_<rank>.csv`): zone, particle diameter, incoming velocity, depo normal,
   outgoing velocity, outcome. The file `depo_zones` sets it: a line `record impacts`.

   The configuration file `depo_zones`, in the case's DATA directory (copied to the run
   directory), one zone per line, `#` starts a comment:

       <zone name> preset <preset id>
       <zone name> constants <k1> <k2> <kappa1> <kappa2> <p> <q> <vc> <mu>
       record impacts
       captured keep
*/

#include "cs_defs.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bft_error.h"
#include "bft_printf.h"
#include "cs_boundary_zone.h"
#include "cs_lagr.h"
#include "cs_lagr_event.h"
#include "cs_lagr_particle.h"
#include "cs_lagr_prototypes.h"
#include "cs_lagr_tracking.h"
#include "cs_mesh.h"
#include "cs_mesh_quantities.h"
#include "cs_parall.h"

#include "depo.h"
#include "depo_code_saturne.h"

BEGIN_C_DECLS

/* One law per boundary zone id (NULL: not a depo zone). */
static DepoWallLaw **_laws = NULL;
static int _n_zones = 0;
static FILE *_record = NULL;
/* Captured particles: removed from the flow (as CS_LAGR_DEPO1), or kept in memory on the
   wall (as CS_LAGR_DEPO2). */
static int _keep_captured = 0;
static unsigned long long _counts[4] = {0, 0, 0, 0};
/* Time spent in depo_apply_f64, s. */
static double _apply_time = 0.0;

static double
_now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void
_close(void)
{
  if (_record != NULL) {
    fclose(_record);
    _record = NULL;
  }
  for (int z = 0; z < _n_zones; z++)
    depo_law_free(_laws[z]);
  free(_laws);
  _laws = NULL;
  _n_zones = 0;
}

static void
_fail(const char *path, int line, const char *what, const char *detail)
{
  bft_error(__FILE__, __LINE__, 0, "depo: %s, line %d: %s%s%s\n", path, line, what,
            detail[0] ? ": " : "", detail);
}

/* Reads `depo_zones` and makes the laws (once per run). */
static void
_read_zones(void)
{
  const char *path = "depo_zones";
  FILE *f = fopen(path, "r");
  if (f == NULL)
    bft_error(__FILE__, __LINE__, 0,
              "depo: cannot open \"%s\" in the run directory (put it in the case's DATA)\n",
              path);

  _n_zones = cs_boundary_zone_n_zones();
  _laws = calloc(_n_zones, sizeof(DepoWallLaw *));
  int record = 0;
  char line[1024];
  for (int number = 1; fgets(line, sizeof line, f) != NULL; number++) {
    char *hash = strchr(line, '#');
    if (hash != NULL)
      *hash = '\0';
    char zone[256], kind[64], rest[700];
    rest[0] = '\0';
    int fields = sscanf(line, "%255s %63s %699[^\n]", zone, kind, rest);
    if (fields <= 0)
      continue;
    if (fields >= 2 && strcmp(zone, "record") == 0 && strcmp(kind, "impacts") == 0) {
      record = 1;
      continue;
    }
    if (fields >= 2 && strcmp(zone, "captured") == 0) {
      if (strcmp(kind, "keep") != 0 && strcmp(kind, "remove") != 0)
        _fail(path, number, "expected \"captured keep\" or \"captured remove\"", kind);
      _keep_captured = strcmp(kind, "keep") == 0;
      continue;
    }
    if (fields < 3)
      _fail(path, number, "expected \"<zone> preset <id>\" or \"<zone> constants <8 numbers>\"", line);
    const cs_zone_t *z = cs_boundary_zone_by_name_try(zone);
    if (z == NULL)
      _fail(path, number, "no boundary zone named", zone);
    DepoWallLaw *law = NULL;
    if (strcmp(kind, "preset") == 0) {
      char id[128];
      if (sscanf(rest, "%127s", id) != 1 || depo_law_preset(id, &law) != DEPO_OK)
        _fail(path, number, "bad preset", depo_last_error());
    }
    else if (strcmp(kind, "constants") == 0) {
      DepoLawParams p;
      char extra[2];
      if (sscanf(rest, "%lf %lf %lf %lf %lf %lf %lf %lf %1s", &p.k1, &p.k2, &p.kappa1,
                 &p.kappa2, &p.p, &p.q, &p.vc, &p.mu, extra) != 8)
        _fail(path, number, "expected 8 numbers: k1 k2 kappa1 kappa2 p q vc mu", rest);
      if (depo_law_new(&p, &law) != DEPO_OK)
        _fail(path, number, "bad constants", depo_last_error());
    }
    else
      _fail(path, number, "expected \"preset\" or \"constants\" after the zone name", kind);
    depo_law_free(_laws[z->id]);
    _laws[z->id] = law;
    bft_printf("depo: zone \"%s\" (id %d): %s %s\n", zone, z->id, kind, rest);
  }
  fclose(f);

  if (record) {
    char name[64];
    if (cs_glob_n_ranks > 1)
      snprintf(name, sizeof name, "depo_impacts_%d.csv", cs_glob_rank_id);
    else
      snprintf(name, sizeof name, "depo_impacts.csv");
    _record = fopen(name, "w");
    if (_record == NULL)
      bft_error(__FILE__, __LINE__, 0, "depo: cannot write %s\n", name);
    fprintf(_record, "zone,diameter,vx,vy,vz,nx,ny,nz,vx_out,vy_out,vz_out,outcome\n");
  }
  atexit(_close);
}

void
depo_cs_setup(cs_lagr_zone_data_t *lagr_bcs)
{
  /* The second-order scheme's correction step recomputes each particle's velocity from its
     values before the step, undoing a rebound set at the contact. */
  if (cs_glob_lagr_time_scheme->t_order != 1)
    bft_error(__FILE__, __LINE__, 0,
              "depo: the wall law needs the first-order Lagrangian scheme; set\n"
              "  cs_glob_lagr_time_scheme->t_order = 1;\n"
              "in cs_user_lagr_model() (it is %d)\n",
              cs_glob_lagr_time_scheme->t_order);
  if (_laws == NULL)
    _read_zones();
  for (int z = 0; z < _n_zones; z++)
    if (_laws[z] != NULL)
      lagr_bcs->zone_type[z] = CS_LAGR_BC_USER;
}

void
depo_cs_counts(unsigned long long counts[4])
{
  for (int k = 0; k < 4; k++)
    counts[k] = _counts[k];
}

double
depo_cs_apply_time(void)
{
  return _apply_time;
}

/* Puts the particle back at the contact point, a millionth of the way towards its cell's
   centre, in that cell. */
static void
_put_back(cs_lagr_particle_set_t  *particles,
          cs_lnum_t                p_id,
          const cs_real_t          c_intersect[3],
          const cs_real_t          centre[3],
          cs_lnum_t                cell_id)
{
  cs_real_t *coords = cs_lagr_particles_attr(particles, p_id, CS_LAGR_COORDS);
  for (int k = 0; k < 3; k++)
    coords[k] = c_intersect[k] + 1e-6 * (centre[k] - c_intersect[k]);
  cs_lagr_particles_set_lnum(particles, p_id, CS_LAGR_CELL_ID, cell_id);
}

void
cs_lagr_user_boundary_interaction(cs_lagr_particle_set_t    *particles,
                                  cs_lnum_t                  p_id,
                                  cs_lnum_t                  face_id,
                                  const cs_real_t            face_norm[3],
                                  const cs_real_t            c_intersect[3],
                                  cs_real_t                  t_intersect,
                                  int                        b_zone_id,
                                  int                       *event_flag,
                                  cs_lagr_tracking_state_t  *tracking_state)
{
  CS_UNUSED(t_intersect);
  if (b_zone_id < 0 || b_zone_id >= _n_zones || _laws[b_zone_id] == NULL)
    bft_error(__FILE__, __LINE__, 0,
              "depo: boundary zone %d is of type CS_LAGR_BC_USER but has no law in depo_zones\n",
              b_zone_id);

  cs_real_t *v = cs_lagr_particles_attr(particles, p_id, CS_LAGR_VELOCITY);
  cs_real_t in[3] = {v[0], v[1], v[2]};

  /* A batch of one, in place on the particle's own velocity. */
  uint8_t outcome = DEPO_INVALID;
  DepoImpactsF64 batch;
  memset(&batch, 0, sizeof batch);
  batch.n = 1;
  batch.vx = &v[0];
  batch.vy = &v[1];
  batch.vz = &v[2];
  /* depo's normal points into the fluid: towards the centre of the face's cell, whichever way
     the mesh orients the face. */
  cs_lnum_t cell_id = cs_glob_mesh->b_face_cells[face_id];
  const cs_real_t *centre = cs_glob_mesh_quantities->cell_cen + 3 * cell_id;
  cs_real_t inward = 0.0;
  for (int k = 0; k < 3; k++)
    inward += face_norm[k] * (centre[k] - c_intersect[k]);
  for (int k = 0; k < 3; k++)
    batch.normal[k] = inward >= 0.0 ? face_norm[k] : -face_norm[k];
  batch.outcome = &outcome;
  double start = _now();
  if (depo_apply_f64(_laws[b_zone_id], &batch, NULL) != DEPO_OK)
    outcome = DEPO_INVALID; /* a face normal not of unit length: leaves v untouched */
  double elapsed = _now() - start;

  /* Code_Saturne may track particles on several OpenMP threads: shared counters and the
     record are updated one thread at a time. */
# pragma omp atomic
  _apply_time += elapsed;
  if (outcome <= DEPO_INVALID) {
#   pragma omp atomic
    _counts[outcome] += 1;
  }
  if (_record != NULL) {
    double d = cs_lagr_particles_get_real(particles, p_id, CS_LAGR_DIAMETER);
#   pragma omp critical (depo_record)
    fprintf(_record, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d\n",
            b_zone_id, d, in[0], in[1], in[2], batch.normal[0], batch.normal[1],
            batch.normal[2], v[0], v[1], v[2], (int)outcome);
  }

  if (outcome == DEPO_REBOUND) {
    _put_back(particles, p_id, c_intersect, centre, cell_id);
    cs_real_t *seen = cs_lagr_particles_attr(particles, p_id, CS_LAGR_VELOCITY_SEEN);
    cs_real_t un = seen[0] * batch.normal[0] + seen[1] * batch.normal[1] + seen[2] * batch.normal[2];
    for (int k = 0; k < 3; k++)
      seen[k] -= 2.0 * un * batch.normal[k];
    *event_flag = *event_flag | CS_EVENT_REBOUND;
    *tracking_state = CS_LAGR_PART_TREATED;
  }
  else if (outcome == DEPO_CAPTURED) {
#   pragma omp atomic
    particles->n_part_dep += 1;
#   pragma omp atomic
    particles->weight_dep += cs_lagr_particles_get_real(particles, p_id, CS_LAGR_STAT_WEIGHT);
    cs_lagr_particles_set_flag(particles, p_id, CS_LAGR_PART_DEPOSITED);
    if (_keep_captured) {
      /* As CS_LAGR_DEPO2 without resuspension: at rest on the wall, inside the cell, kept in
         memory, and fixed (without CS_LAGR_PART_FIXED the particle equations would go on
         moving it). */
      cs_lagr_particles_set_flag(particles, p_id, CS_LAGR_PART_FIXED);
      _put_back(particles, p_id, c_intersect, centre, cell_id);
      cs_real_t *seen = cs_lagr_particles_attr(particles, p_id, CS_LAGR_VELOCITY_SEEN);
      for (int k = 0; k < 3; k++)
        seen[k] = 0.0;
      *event_flag = *event_flag | CS_EVENT_DEPOSITION;
      *tracking_state = CS_LAGR_PART_STUCK;
    }
    else {
      /* As CS_LAGR_DEPO1: removed from the flow, at the contact point. */
      cs_real_t *coords = cs_lagr_particles_attr(particles, p_id, CS_LAGR_COORDS);
      for (int k = 0; k < 3; k++)
        coords[k] = c_intersect[k];
      *event_flag = *event_flag | (CS_EVENT_OUTFLOW | CS_EVENT_DEPOSITION);
      *tracking_state = CS_LAGR_PART_OUT;
    }
  }
  else if (outcome == DEPO_SKIPPED) {
    /* The step's displacement crossed the face but the velocity at its end already points
       away from the wall (turbulent dispersion, drag): not an impact. The particle is put
       back at the contact point with its velocity, as for a rebound. */
    _put_back(particles, p_id, c_intersect, centre, cell_id);
    *tracking_state = CS_LAGR_PART_TREATED;
  }
  else {
    *event_flag = *event_flag | CS_EVENT_OUTFLOW;
    *tracking_state = CS_LAGR_PART_OUT;
  }
}

END_C_DECLS
