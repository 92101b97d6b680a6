# The channel case: the box mesh written by box_mesh.py, and for a particle stage the
# flow stage's checkpoint to restart from (CHANNEL_RESTART, set by run_channel.sh). The
# wall-function stage links libdepo from the install prefix CHANNEL_DEPO_PREFIX (set by
# run_channel.sh for that stage only) and compiles the case with CHANNEL_DEPO defined.
import os


def define_domain_parameters(domain):
    if domain.param is None:
        domain.preprocess_on_restart = False
        domain.mesh_input = None
        domain.partition_input = None
        domain.restart_input = os.environ.get("CHANNEL_RESTART") or None
        domain.mesh_dir = None
        domain.meshes = ["box.msh"]
        prefix = os.environ.get("CHANNEL_DEPO_PREFIX")
        if prefix:
            domain.compile_cflags = "-DCHANNEL_DEPO -I%s/include" % prefix
            domain.compile_libs = "-L%s/lib -ldepo -Wl,-rpath,%s/lib" % (prefix, prefix)
