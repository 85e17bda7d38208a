build-native/core/scene/sb_chart.o: core/scene/sb_chart.c \
 core/scene/sb_geometry.h core/scene/sb_scene.h core/base/sb_common.h
core/scene/sb_geometry.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
