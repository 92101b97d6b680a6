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

   A zone can instead take depo's deposition wall function (`<zone> wall-function <correlation>`),
   for meshes that do not resolve the near-wall layer: the zone becomes Code_Saturne's elastic
   CS_LAGR_REBOUND, and depo_cs_wall_function(), called once per Lagrangian step from
   cs_user_lagr_extra_operations(), deposits each particle of a cell with a face on the zone
   with the chance depo_wall_function_probability() gives for that face: the correlation's
   deposition velocity at the face's wall-function friction velocity (Code_Saturne's boundary
   field `ustar`), over the cell's extent normal to the face (twice its centre's distance to the
   face's plane). A particle drawn is deposited as CS_LAGR_DEPO1 deposits it: counted in the
   particle set's deposited (and outgoing) number and weight, and removed from the set. Sink
   only: no wall law decides between rebound and capture there.

   The configuration file `depo_zones`, in the case's DATA directory (copied to the run
   directory), one zone per line, `#` starts a comment:

       <zone name> preset <preset id>
       <zone name> constants <k1> <k2> <kappa1> <kappa2> <p> <q> <vc> <mu>
       <zone name> wall-function wood | papavergos-hedley | lai-nazaroff | hussein
       record impacts
       captured keep
*/

#include "cs_defs.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bft_error.h"
#include "bft_printf.h"
#include "cs_boundary_zone.h"
#include "cs_field.h"
#include "cs_lagr.h"
#include "cs_lagr_event.h"
#include "cs_lagr_particle.h"
#include "cs_lagr_prototypes.h"
#include "cs_lagr_tracking.h"
#include "cs_mesh.h"
#include "cs_mesh_quantities.h"
#include "cs_parall.h"
#include "cs_physical_constants.h"
#include "cs_random.h"

#include "depo.h"
#include "depo_code_saturne.h"

BEGIN_C_DECLS

/* One law per boundary zone id (NULL: not a depo zone). */
static DepoWallLaw **_laws = NULL;
static int _n_zones = 0;
/* The wall function's correlation per boundary zone id (-1: not a wall-function zone). */
static int *_wf_correlation = NULL;
/* The wall-function faces of each cell (CSR, built at the first step) and, per face, its zone,
   the cell's extent normal to it (m) and depo's orientation of the surface. */
static cs_lnum_t *_wf_cell_index = NULL;
static cs_lnum_t *_wf_cell_faces = NULL;
static double *_wf_layer = NULL;
static int32_t *_wf_orientation = NULL;
static unsigned long long _wf_deposits = 0;
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
  free(_wf_correlation);
  _wf_correlation = NULL;
  free(_wf_cell_index);
  free(_wf_cell_faces);
  free(_wf_layer);
  free(_wf_orientation);
  _wf_cell_index = NULL;
  _wf_cell_faces = NULL;
  _wf_layer = NULL;
  _wf_orientation = NULL;
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
  _wf_correlation = malloc(_n_zones * sizeof(int));
  for (int z = 0; z < _n_zones; z++)
    _wf_correlation[z] = -1;
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
    if (strcmp(kind, "wall-function") == 0) {
      char name[128], extra[2];
      int n = sscanf(rest, "%127s %1s", name, extra);
      int correlation = -1;
      if (n >= 1 && strcmp(name, "wood") == 0)
        correlation = DEPO_CORRELATION_WOOD;
      else if (n >= 1 && strcmp(name, "papavergos-hedley") == 0)
        correlation = DEPO_CORRELATION_PAPAVERGOS_HEDLEY;
      else if (n >= 1 && strcmp(name, "lai-nazaroff") == 0)
        correlation = DEPO_CORRELATION_LAI_NAZAROFF;
      else if (n >= 1 && strcmp(name, "hussein") == 0)
        correlation = DEPO_CORRELATION_HUSSEIN;
      if (correlation < 0 || n != 1)
        _fail(path, number,
              "expected \"<zone> wall-function wood|papavergos-hedley|lai-nazaroff|hussein\" (a "
              "sink: no wall law after it)", rest);
      depo_law_free(_laws[z->id]);
      _laws[z->id] = NULL;
      _wf_correlation[z->id] = correlation;
      bft_printf("depo: zone \"%s\" (id %d): wall-function %s\n", zone, z->id, name);
      continue;
    }
    _wf_correlation[z->id] = -1;
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
      _fail(path, number, "expected \"preset\", \"constants\" or \"wall-function\" after the zone name", kind);
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
  for (int z = 0; z < _n_zones; z++) {
    if (_laws[z] != NULL)
      lagr_bcs->zone_type[z] = CS_LAGR_BC_USER;
    /* A wall-function zone reflects: its deposits are drawn in the wall cells, not at the
       wall, so that none deposits twice. */
    if (_wf_correlation[z] >= 0)
      lagr_bcs->zone_type[z] = CS_LAGR_REBOUND;
  }
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

/* The wall-function faces of each cell, each face's layer (the cell's extent normal to it:
   twice the distance from the cell's centre to the face's plane) and orientation (from the
   normal into the fluid against gravity: a floor faces up, a ceiling down; a wall otherwise
   or without gravity). */
static void
_wf_build(void)
{
  const cs_mesh_t *m = cs_glob_mesh;
  const cs_mesh_quantities_t *q = cs_glob_mesh_quantities;
  const int *zone_of_face = cs_boundary_zone_face_zone_id();
  const cs_real_t *g = cs_glob_physical_constants->gravity;
  double g_norm = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);

  _wf_cell_index = calloc(m->n_cells + 1, sizeof(cs_lnum_t));
  for (cs_lnum_t f = 0; f < m->n_b_faces; f++)
    if (_wf_correlation[zone_of_face[f]] >= 0)
      _wf_cell_index[m->b_face_cells[f] + 1] += 1;
  for (cs_lnum_t c = 0; c < m->n_cells; c++)
    _wf_cell_index[c + 1] += _wf_cell_index[c];
  cs_lnum_t n = _wf_cell_index[m->n_cells];
  _wf_cell_faces = malloc((n > 0 ? n : 1) * sizeof(cs_lnum_t));
  _wf_layer = calloc(m->n_b_faces, sizeof(double));
  _wf_orientation = calloc(m->n_b_faces, sizeof(int32_t));
  cs_lnum_t *fill = malloc(m->n_cells * sizeof(cs_lnum_t));
  for (cs_lnum_t c = 0; c < m->n_cells; c++)
    fill[c] = _wf_cell_index[c];
  for (cs_lnum_t f = 0; f < m->n_b_faces; f++) {
    if (_wf_correlation[zone_of_face[f]] < 0)
      continue;
    cs_lnum_t c = m->b_face_cells[f];
    _wf_cell_faces[fill[c]++] = f;
    const cs_real_t *u = q->b_face_normal + 3 * f;
    const cs_real_t *xf = q->b_face_cog + 3 * f;
    const cs_real_t *xc = q->cell_cen + 3 * c;
    double area = q->b_face_surf[f], d = 0.0, up = 0.0;
    for (int k = 0; k < 3; k++)
      d += u[k] / area * (xc[k] - xf[k]);
    /* d: the centre's signed distance along the face's normal; the normal into the fluid is
       the unit normal times the sign of d. */
    _wf_layer[f] = 2.0 * fabs(d);
    for (int k = 0; k < 3; k++)
      up -= (d >= 0.0 ? 1.0 : -1.0) * u[k] / area * (g_norm > 0.0 ? g[k] / g_norm : 0.0);
    _wf_orientation[f] = up > 0.7 ? DEPO_SURFACE_FLOOR
                       : up < -0.7 ? DEPO_SURFACE_CEILING : DEPO_SURFACE_WALL;
  }
  free(fill);
}

/* Removes particle p_id from the set: the set's last particle takes its place. */
static void
_wf_remove(cs_lagr_particle_set_t *particles, cs_lnum_t p_id)
{
  size_t extents = particles->p_am->extents;
  cs_lnum_t last = particles->n_particles - 1;
  if (p_id != last)
    memcpy(particles->p_buffer + extents * p_id, particles->p_buffer + extents * last, extents);
  particles->n_particles = last;
}

void
depo_cs_wall_function(void)
{
  if (_wf_correlation == NULL)
    bft_error(__FILE__, __LINE__, 0,
              "depo: depo_cs_wall_function() before depo_cs_setup(): call depo_cs_setup() from "
              "cs_user_lagr_boundary_conditions()\n");
  int any = 0;
  for (int z = 0; z < _n_zones; z++)
    any = any || _wf_correlation[z] >= 0;
  if (!any)
    return;
  const cs_field_t *ustar = cs_field_by_name_try("ustar");
  if (ustar == NULL)
    bft_error(__FILE__, __LINE__, 0,
              "depo: the wall function needs the wall-function friction velocity of each face:\n"
              "  cs_field_find_or_create(\"ustar\", CS_FIELD_PROPERTY, "
              "CS_MESH_LOCATION_BOUNDARY_FACES, 1, false);\n"
              "in cs_user_parameters()\n");
  if (_wf_cell_index == NULL)
    _wf_build();

  const cs_mesh_t *m = cs_glob_mesh;
  const int *zone_of_face = cs_boundary_zone_face_zone_id();
  cs_lagr_particle_set_t *particles = cs_glob_lagr_particle_set;
  const cs_fluid_properties_t *fluid = cs_glob_fluid_properties;
  const cs_real_t *g = cs_glob_physical_constants->gravity;
  DepoAir air = {fluid->t0, fluid->p0, fluid->ro0, fluid->viscl0};
  double gravity = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  double dt = cs_glob_lagr_time_step->dtp;

  /* Every (particle, wall-function face of its cell) pair; a cell with faces on two walls (a
     duct's corner) gives each face its own chance. */
  cs_lnum_t n_pairs = 0;
  for (cs_lnum_t i = 0; i < particles->n_particles; i++) {
    cs_lnum_t c = cs_lagr_particles_get_lnum(particles, i, CS_LAGR_CELL_ID);
    if (c >= 0 && c < m->n_cells)
      n_pairs += _wf_cell_index[c + 1] - _wf_cell_index[c];
  }
  if (n_pairs == 0)
    return;
  cs_lnum_t *pair_particle = malloc(n_pairs * sizeof(cs_lnum_t));
  cs_lnum_t *pair_face = malloc(n_pairs * sizeof(cs_lnum_t));
  double *u = malloc(n_pairs * sizeof(double)), *layer = malloc(n_pairs * sizeof(double));
  double *d = malloc(n_pairs * sizeof(double)), *rho = malloc(n_pairs * sizeof(double));
  double *p = malloc(n_pairs * sizeof(double));
  cs_real_t *draw = malloc(n_pairs * sizeof(cs_real_t));
  unsigned char *out = calloc(particles->n_particles, 1);

  /* One batch per correlation and orientation. */
  for (int o = DEPO_SURFACE_FLOOR; o <= DEPO_SURFACE_WALL; o++) {
    for (int z = 0; z < _n_zones; z++) {
      if (_wf_correlation[z] < 0)
        continue;
      size_t n = 0;
      for (cs_lnum_t i = 0; i < particles->n_particles; i++) {
        cs_lnum_t c = cs_lagr_particles_get_lnum(particles, i, CS_LAGR_CELL_ID);
        if (c < 0 || c >= m->n_cells
            || cs_lagr_particles_get_flag(particles, i, CS_LAGR_PART_DEPOSITED))
          continue;
        for (cs_lnum_t j = _wf_cell_index[c]; j < _wf_cell_index[c + 1]; j++) {
          cs_lnum_t f = _wf_cell_faces[j];
          if (zone_of_face[f] != z || _wf_orientation[f] != o)
            continue;
          double diameter = cs_lagr_particles_get_real(particles, i, CS_LAGR_DIAMETER);
          double mass = cs_lagr_particles_get_real(particles, i, CS_LAGR_MASS);
          pair_particle[n] = i;
          pair_face[n] = f;
          u[n] = ustar->val[f];
          layer[n] = _wf_layer[f];
          d[n] = diameter;
          rho[n] = mass / (3.14159265358979323846 / 6.0 * diameter * diameter * diameter);
          n++;
        }
      }
      if (n == 0)
        continue;
      if (depo_wall_function_probability(_wf_correlation[z], o, &air, gravity, dt, n, u, layer,
                                         d, rho, p) != DEPO_OK)
        bft_error(__FILE__, __LINE__, 0, "depo: wall function on zone %d: %s\n", z,
                  depo_last_error());
      cs_random_uniform((cs_lnum_t)n, draw);
      for (size_t k = 0; k < n; k++)
        if (draw[k] < p[k])
          out[pair_particle[k]] = 1;
    }
  }

  /* Deposited as CS_LAGR_DEPO1 deposits: counted, and removed from the set. From the end
     down, so that the particle moved into a removed one's place has been drawn already. */
  for (cs_lnum_t i = particles->n_particles - 1; i >= 0; i--) {
    if (!out[i])
      continue;
    double w = cs_lagr_particles_get_real(particles, i, CS_LAGR_STAT_WEIGHT);
    particles->n_part_dep += 1;
    particles->weight_dep += w;
    particles->n_part_out += 1;
    particles->weight_out += w;
    particles->weight -= w;
    _wf_deposits += 1;
    _wf_remove(particles, i);
  }

  free(out);
  free(draw);
  free(p);
  free(rho);
  free(d);
  free(layer);
  free(u);
  free(pair_face);
  free(pair_particle);
}

unsigned long long
depo_cs_wall_function_deposits(void)
{
  return _wf_deposits;
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

  /* Code_Saturne counts its "particle/boundary interactions" statistic (Part_impact_number)
     for its own wall types only: a depo zone's contacts, rebounds and captures, are counted
     here as a CS_LAGR_REBOUND or CS_LAGR_DEPO1 face counts them. */
  if (   (outcome == DEPO_REBOUND || outcome == DEPO_CAPTURED)
      && cs_glob_lagr_boundary_interactions->has_part_impact_nbr > 0 && bound_stat != NULL) {
    cs_real_t w = cs_lagr_particles_get_real(particles, p_id, CS_LAGR_STAT_WEIGHT);
#   pragma omp atomic
    bound_stat[cs_glob_lagr_boundary_interactions->inbr * cs_glob_mesh->n_b_faces + face_id] += w;
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
      /* CS_EVENT_DEPOSITION alone, as Code_Saturne's CS_LAGR_DEPO1 flags it: its boundary
         statistics take an event flagged CS_EVENT_OUTFLOW for a particle leaving through an
         outlet, and set its impact angle and velocity to 0. */
      *event_flag = *event_flag | CS_EVENT_DEPOSITION;
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
