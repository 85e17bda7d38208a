build-native/core/scene/sb_json_pos.o: core/scene/sb_json_pos.c \
 core/scene/sb_json_pos.h
core/scene/sb_json_pos.h:
