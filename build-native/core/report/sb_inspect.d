build-native/core/report/sb_inspect.o: core/report/sb_inspect.c \
 core/report/sb_inspect.h core/problem/sb_method.h core/scene/sb_scene.h \
 core/base/sb_common.h core/base/sb_params.h core/base/sb_common.h \
 core/linalg/sb_sparse.h core/problem/sb_material_state.h \
 core/base/sb_context.h core/base/sb_params.h core/base/sb_stats.h \
 core/record/sb_record.h core/base/sb_stats.h \
 core/problem/sb_material_state.h
core/report/sb_inspect.h:
core/problem/sb_method.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/base/sb_params.h:
core/base/sb_common.h:
core/linalg/sb_sparse.h:
core/problem/sb_material_state.h:
core/base/sb_context.h:
core/base/sb_params.h:
core/base/sb_stats.h:
core/record/sb_record.h:
core/base/sb_stats.h:
core/problem/sb_material_state.h:
