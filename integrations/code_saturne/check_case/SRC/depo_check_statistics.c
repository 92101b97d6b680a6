/* Check case: at the last step, every boundary face's zone, area and Code_Saturne's boundary
   statistics (its "particle/boundary interactions" count and every boundary-face field of the
   Lagrangian statistics) are written to depo_boundary_stats.csv (depo_boundary_stats_<rank>.csv
   on each rank of a parallel run), for the test to compare with depo's contacts. */

#include "cs_defs.h"

#include <stdio.h>
#include <string.h>

#include "bft_error.h"
#include "cs_boundary_zone.h"
#include "cs_field.h"
#include "cs_lagr.h"
#include "cs_mesh.h"
#include "cs_mesh_location.h"
#include "cs_mesh_quantities.h"
#include "cs_prototypes.h"
#include "cs_time_step.h"

BEGIN_C_DECLS

void
cs_user_extra_operations(cs_domain_t *domain)
{
  CS_UNUSED(domain);
  if (cs_glob_time_step->nt_cur != cs_glob_time_step->nt_max)
    return;
  char name[64];
  if (cs_glob_n_ranks > 1)
    snprintf(name, sizeof name, "depo_boundary_stats_%d.csv", cs_glob_rank_id);
  else
    snprintf(name, sizeof name, "depo_boundary_stats.csv");
  FILE *out = fopen(name, "w");
  if (out == NULL)
    bft_error(__FILE__, __LINE__, 0, "cannot write %s\n", name);

  const cs_mesh_t *m = cs_glob_mesh;
  const int *zone_of_face = cs_boundary_zone_face_zone_id();
  const cs_lagr_boundary_interactions_t *bi = cs_glob_lagr_boundary_interactions;
  int fields[64], n_fields = 0;
  for (int f_id = 0; f_id < cs_field_n_fields() && n_fields < 64; f_id++) {
    const cs_field_t *f = cs_field_by_id(f_id);
    if (f->location_id == CS_MESH_LOCATION_BOUNDARY_FACES && f->dim == 1
        && strstr(f->name, "particle") != NULL && f->val != NULL)
      fields[n_fields++] = f_id;
  }
  fprintf(out, "zone,area,impact_number");
  for (int i = 0; i < n_fields; i++)
    fprintf(out, ",%s", cs_field_by_id(fields[i])->name);
  fprintf(out, "\n");
  for (cs_lnum_t face = 0; face < m->n_b_faces; face++) {
    double impacts = bi->has_part_impact_nbr > 0 ? bound_stat[bi->inbr * m->n_b_faces + face] : 0.0;
    fprintf(out, "%d,%.17g,%.17g", zone_of_face[face], cs_glob_mesh_quantities->b_face_surf[face],
            impacts);
    for (int i = 0; i < n_fields; i++)
      fprintf(out, ",%.17g", cs_field_by_id(fields[i])->val[face]);
    fprintf(out, "\n");
  }
  fclose(out);
}

END_C_DECLS
