#define SB_BUILD_ID "d917324-dirty+native(-O3 -march=native)"
