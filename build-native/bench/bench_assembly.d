build-native/bench/bench_assembly: bench/bench_assembly.c \
 core/base/sb_context.h core/base/sb_params.h core/base/sb_common.h \
 core/base/sb_stats.h core/linalg/sb_linsolve.h core/linalg/sb_sparse.h \
 core/base/sb_common.h core/base/sb_stats.h core/problem/sb_method.h \
 core/scene/sb_scene.h core/base/sb_params.h core/linalg/sb_sparse.h \
 core/problem/sb_material_state.h core/solvers/sb_solver.h \
 core/problem/sb_problem.h core/problem/sb_method.h \
 core/base/sb_sysinfo.h
core/base/sb_context.h:
core/base/sb_params.h:
core/base/sb_common.h:
core/base/sb_stats.h:
core/linalg/sb_linsolve.h:
core/linalg/sb_sparse.h:
core/base/sb_common.h:
core/base/sb_stats.h:
core/problem/sb_method.h:
core/scene/sb_scene.h:
core/base/sb_params.h:
core/linalg/sb_sparse.h:
core/problem/sb_material_state.h:
core/solvers/sb_solver.h:
core/problem/sb_problem.h:
core/problem/sb_method.h:
core/base/sb_sysinfo.h:
