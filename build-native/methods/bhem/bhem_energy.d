build-native/methods/bhem/bhem_energy.o: methods/bhem/bhem_energy.c \
 methods/bhem/bhem.h core/problem/sb_method.h core/scene/sb_scene.h \
 core/base/sb_common.h core/base/sb_params.h core/base/sb_common.h \
 core/linalg/sb_sparse.h core/problem/sb_material_state.h \
 core/scene/sb_geometry.h core/scene/sb_scene.h core/shell/sb_shell.h \
 core/shell/sb_material.h core/linalg/sb_assemble.h
methods/bhem/bhem.h:
core/problem/sb_method.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/base/sb_params.h:
core/base/sb_common.h:
core/linalg/sb_sparse.h:
core/problem/sb_material_state.h:
core/scene/sb_geometry.h:
core/scene/sb_scene.h:
core/shell/sb_shell.h:
core/shell/sb_material.h:
core/linalg/sb_assemble.h:
