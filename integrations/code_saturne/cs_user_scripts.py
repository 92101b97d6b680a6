# Every case of this directory: the box mesh written by box_mesh.py, and libdepo found through DEPO_PREFIX
# (an install prefix of libdepo: include/depo.h and lib/libdepo.so); with DEPO_CS_RESTART, the
# checkpoint directory of an earlier run to restart from (the duct's particle runs).
import os


def define_domain_parameters(domain):
    if domain.param is None:
        domain.preprocess_on_restart = False
        domain.mesh_input = None
        domain.partition_input = None
        domain.restart_input = os.environ.get("DEPO_CS_RESTART") or None
        domain.mesh_dir = None
        domain.meshes = [os.environ.get("DEPO_CS_MESH", "box.msh")]
        prefix = os.environ["DEPO_PREFIX"]
        domain.compile_cflags = "-I%s/include" % prefix
        domain.compile_cxxflags = None
        domain.compile_fcflags = None
        domain.compile_libs = "-L%s/lib -ldepo -Wl,-rpath,%s/lib" % (prefix, prefix)
