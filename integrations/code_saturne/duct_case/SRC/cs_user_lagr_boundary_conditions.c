/* Duct: in a particle run (restarted from the flow stage's developed flow), particles of 10,
   30 and 100 um (1000 kg/m^3) enter with the air at the inlet, 20 of each size per step over
   the run's first 2 s (duct.h), and leave at the outlet. The walls are Code_Saturne's own
   deposition walls (CS_LAGR_DEPO2: a particle that reaches one deposits and stays), which
   are a perfect sink ("sink") or, with Code_Saturne's deposition model on ("model",
   cs_user_lagr_model.c), the walls the model's particles reach; or depo's law ("depo"), or
   depo's deposition wall function ("wall-function"), the last two with the zones of
   DATA/depo_zones; as the file `walls` in DATA says, which says "flow" for the flow stage. */

#include "cs_defs.h"

#include <stdio.h>
#include <string.h>

#include "bft_error.h"
#include "cs_boundary_zone.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"
#include "cs_time_step.h"

#include "depo_code_saturne.h"
#include "duct.h"

BEGIN_C_DECLS

int
duct_walls_mode(void)
{
  static int mode = -1;
  if (mode < 0) {
    char word[16] = "";
    FILE *f = fopen("walls", "r");
    if (f == NULL || fscanf(f, "%15s", word) != 1)
      bft_error(__FILE__, __LINE__, 0, "duct: DATA/walls must say \"flow\", \"sink\", "
                "\"depo\", \"wall-function\" or \"model\"\n");
    fclose(f);
    if (strcmp(word, "sink") == 0)
      mode = DUCT_SINK;
    else if (strcmp(word, "depo") == 0)
      mode = DUCT_DEPO;
    else if (strcmp(word, "wall-function") == 0)
      mode = DUCT_WALL_FUNCTION;
    else if (strcmp(word, "model") == 0)
      mode = DUCT_MODEL;
    else if (strcmp(word, "flow") == 0)
      mode = DUCT_FLOW;
    else
      bft_error(__FILE__, __LINE__, 0, "duct: DATA/walls says \"%s\", not flow, sink, depo, "
                "wall-function or model\n", word);
  }
  return mode;
}

void
cs_user_lagr_boundary_conditions(const int  bc_type[])
{
  CS_UNUSED(bc_type);
  cs_lagr_zone_data_t *bcs = cs_lagr_get_boundary_conditions();
  const char *walls[3] = {"floor", "ceiling", "sides"};
  for (int w = 0; w < 3; w++)
    bcs->zone_type[cs_boundary_zone_by_name(walls[w])->id] = CS_LAGR_DEPO2;
  bcs->zone_type[cs_boundary_zone_by_name("outlet")->id] = CS_LAGR_OUTLET;
  if (duct_walls_mode() == DUCT_DEPO || duct_walls_mode() == DUCT_WALL_FUNCTION)
    depo_cs_setup(bcs);

  int inlet = cs_boundary_zone_by_name("inlet")->id;
  bcs->zone_type[inlet] = CS_LAGR_INLET;
  int step = cs_glob_time_step->nt_cur - DUCT_FLOW_STEPS;
  for (int set_id = 0; set_id < DUCT_SIZES; set_id++) {
    cs_lagr_injection_set_t *set = cs_lagr_get_injection_set(bcs, inlet, set_id);
    set->n_inject = (step >= DUCT_FIRST_STEP && step <= DUCT_LAST_STEP) ? DUCT_PER_STEP : 0;
    set->injection_frequency = 1;
    set->velocity_profile = -1; /* the fluid's velocity */
    set->stat_weight = 1.0;
    set->flow_rate = 0.0;
    set->diameter = duct_diameters[set_id];
    set->diameter_variance = 0.0;
    set->density = DUCT_DENSITY;
    set->temperature_profile = 0;
  }
}

END_C_DECLS
