#define SB_BUILD_ID "c869a1c-dirty+native(-O3 -march=native)"
