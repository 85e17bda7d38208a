/* sb_test.h — a tiny test harness.  Each test binary lists its tests and
 * calls sb_test_main(); the last line it prints is "NAME: P passed, F failed",
 * which scripts/test_summary.sh sums into the suite's closing line. */
#ifndef SB_TEST_H
#define SB_TEST_H

#include <math.h>
#include <stdio.h>

typedef struct sb_test_state {
    int failed;          /* checks failed in the current test */
    int checks;
} sb_test_state;

typedef void (*sb_test_fn)(sb_test_state *T);
typedef struct sb_test_case { const char *name; sb_test_fn fn; } sb_test_case;

void sb_test_fail(sb_test_state *T, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
int  sb_test_main(int argc, char **argv, const sb_test_case *cases);
/* repository root (SB_ROOT or "."), and the shellbench binary (SB_BIN) */
const char *sb_test_root(void);
const char *sb_test_bin(void);
/* relative error |a-b| / max(|b|, tiny) */
double sb_rel_err(double a, double b);

#define SB_TEST(fn) static void fn(sb_test_state *T)
#define SB_CASE(fn) { #fn, fn }
#define SB_END { 0, 0 }

#define CHECK(c) do { T->checks++; if (!(c)) sb_test_fail(T, __FILE__, __LINE__, "%s", #c); } while (0)
#define CHECK_MSG(c, ...) do { T->checks++; if (!(c)) sb_test_fail(T, __FILE__, __LINE__, __VA_ARGS__); } while (0)
#define CHECK_NEAR(a, b, tol) do { double a_ = (a), b_ = (b), t_ = (tol); T->checks++; \
    if (!(fabs(a_ - b_) <= t_)) sb_test_fail(T, __FILE__, __LINE__, "%s = %.12g, %s = %.12g, |diff| %.3g > %.3g", \
        #a, a_, #b, b_, fabs(a_ - b_), t_); } while (0)
#define CHECK_REL(a, b, rtol) do { double a_ = (a), b_ = (b), t_ = (rtol); T->checks++; \
    if (!(sb_rel_err(a_, b_) <= t_)) sb_test_fail(T, __FILE__, __LINE__, "%s = %.12g, %s = %.12g, rel %.3g > %.3g", \
        #a, a_, #b, b_, sb_rel_err(a_, b_), t_); } while (0)
#define CHECK_EQ_INT(a, b) do { long a_ = (long)(a), b_ = (long)(b); T->checks++; \
    if (a_ != b_) sb_test_fail(T, __FILE__, __LINE__, "%s = %ld, expected %s = %ld", #a, a_, #b, b_); } while (0)

#endif
