/* Reads `channel_run` (see channel.h). */

#include "cs_defs.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bft_error.h"

#include "channel.h"

BEGIN_C_DECLS

const channel_run_t *
channel_run(void)
{
  static channel_run_t run = {-1, 0, 0, 0, CHANNEL_DT_PARTICLES, {0}};
  if (run.stage >= 0)
    return &run;
  for (int c = 0; c < CHANNEL_CLASSES; c++)
    run.injected[c] = 1;
  FILE *f = fopen("channel_run", "r");
  if (f == NULL)
    bft_error(__FILE__, __LINE__, 0, "channel: no file channel_run in DATA\n");
  char key[32], value[128];
  while (fscanf(f, "%31s %127s", key, value) == 2) {
    if (strcmp(key, "stage") == 0) {
      if (strcmp(value, "flow") == 0)
        run.stage = CHANNEL_FLOW;
      else if (strcmp(value, "model") == 0)
        run.stage = CHANNEL_MODEL;
      else if (strcmp(value, "no-model") == 0)
        run.stage = CHANNEL_NO_MODEL;
      else if (strcmp(value, "wall-function") == 0)
        run.stage = CHANNEL_WALL_FUNCTION;
      else
        bft_error(__FILE__, __LINE__, 0,
                  "channel: stage \"%s\" is not flow, model, no-model or wall-function\n", value);
    }
    else if (strcmp(key, "classes") == 0) {
      for (int c = 0; c < CHANNEL_CLASSES; c++)
        run.injected[c] = 0;
      for (char *t = strtok(value, ","); t != NULL; t = strtok(NULL, ",")) {
        int c = 0;
        while (c < CHANNEL_CLASSES && fabs(atof(t) - channel_tau_plus[c]) > 1e-9 * channel_tau_plus[c])
          c++;
        if (c == CHANNEL_CLASSES)
          bft_error(__FILE__, __LINE__, 0, "channel: no class of tau+ %s (channel.h)\n", t);
        run.injected[c] = 1;
      }
    }
    else if (strcmp(key, "particles") == 0)
      run.particles = atol(value);
    else if (strcmp(key, "flow_steps") == 0)
      run.flow_steps = atoi(value);
    else if (strcmp(key, "particle_steps") == 0)
      run.particle_steps = atoi(value);
    else if (strcmp(key, "particle_dt") == 0)
      run.particle_dt = atof(value);
    else
      bft_error(__FILE__, __LINE__, 0, "channel: unknown key \"%s\" in channel_run\n", key);
  }
  fclose(f);
  if (run.stage < 0 || run.flow_steps <= 0
      || (run.stage != CHANNEL_FLOW && (run.particles <= 0 || run.particle_steps <= 0
                                           || !(run.particle_dt > 0.0))))
    bft_error(__FILE__, __LINE__, 0, "channel: channel_run needs stage, flow_steps, and for "
              "a particle stage particles, particle_steps and a positive particle_dt\n");
  return &run;
}

END_C_DECLS
