/* Times the C that CasADi generated from Pinocchio's RNEA (pinocchio_casadi.cpp:
 * `casadi_q_cse`, after CasADi's common subexpression elimination), called through a pointer
 * from this separately compiled file, with the protocol of pinocchio_rnea.cpp: the states of
 * NAME.states (the benchmark's 1,024 seeded states and tendyn's Q at each), agreement with
 * tendyn's Q first (max-norm relative error), then 0.3 s of warm-up and the median ns per
 * call of 51 samples of at least 2 ms. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

/* CasADi's generated code defaults to these (its casadi_real and casadi_int). */
typedef double casadi_real;
typedef long long int casadi_int;
int casadi_q_cse(const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w,
                 int mem);
int casadi_q_cse_work(casadi_int* sz_arg, casadi_int* sz_res, casadi_int* sz_iw,
                      casadi_int* sz_w);
casadi_int casadi_q_cse_n_in(void);
const casadi_int* casadi_q_cse_sparsity_in(casadi_int i);

/* Called through a pointer, as a caller of another translation unit would. */
static int (*volatile eval)(const casadi_real**, casadi_real**, casadi_int*, casadi_real*,
                            int) = casadi_q_cse;

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int by_value(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

static void* allocate(size_t bytes) {
  void* p = malloc(bytes);
  if (!p) {
    fprintf(stderr, "casadi_time: out of memory\n");
    exit(2);
  }
  return p;
}

enum { CAPACITY = 4096 };

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: casadi_time NAME.states\n");
    return 2;
  }
  FILE* in = fopen(argv[1], "r");
  int n, count = 0;
  if (!in) {
    perror(argv[1]);
    return 2;
  }
  /* Each input of casadi_q_cse (q, q̇, q̈) is a dense column of n (sparsity: rows, columns, …). */
  if (fscanf(in, "%d", &n) != 1 || n < 1 || casadi_q_cse_n_in() != 3 ||
      casadi_q_cse_sparsity_in(0)[0] != n) {
    fprintf(stderr, "%s: not the states of this function's mechanism\n", argv[1]);
    return 2;
  }
  double* states = allocate(sizeof(double) * 4 * n * CAPACITY);
  for (; count < CAPACITY; ++count) {
    int i = 0;
    while (i < 4 * n && fscanf(in, "%lf", &states[4 * n * count + i]) == 1) ++i;
    if (i == 0) break;
    if (i < 4 * n) {
      fprintf(stderr, "%s: state %d is incomplete\n", argv[1], count);
      return 2;
    }
  }
  double extra;
  if (count == 0 || fscanf(in, "%lf", &extra) == 1) {
    fprintf(stderr, "%s: %s\n", argv[1], count == 0 ? "no states" : "more states than 4,096");
    return 2;
  }
  fclose(in);
  casadi_int sz_arg, sz_res, sz_iw, sz_w;
  if (casadi_q_cse_work(&sz_arg, &sz_res, &sz_iw, &sz_w) != 0) return 2;
  const casadi_real** arg = allocate(sizeof(casadi_real*) * (sz_arg > 3 ? sz_arg : 3));
  casadi_real** res = allocate(sizeof(casadi_real*) * (sz_res > 1 ? sz_res : 1));
  casadi_int* iw = allocate(sizeof(casadi_int) * (sz_iw + 1));
  casadi_real* w = allocate(sizeof(casadi_real) * (sz_w + 1));
  double* out = allocate(sizeof(double) * n);
  res[0] = out;
  double worst = 0, sink = 0;
  for (int s = 0; s < count; ++s) {
    const double* x = &states[4 * n * s];
    arg[0] = x, arg[1] = x + n, arg[2] = x + 2 * n;
    if (eval(arg, res, iw, w, 0) != 0) return 2;
    double err = 0, size = 1e-300;
    for (int j = 0; j < n; ++j) {
      err = fmax(err, fabs(out[j] - x[3 * n + j]));
      size = fmax(size, fabs(x[3 * n + j]));
    }
    worst = fmax(worst, err / size);
  }
  double t0 = now();
  long passes = 0;
  while (now() - t0 < 0.3) {
    for (int s = 0; s < count; ++s) {
      const double* x = &states[4 * n * s];
      arg[0] = x, arg[1] = x + n, arg[2] = x + 2 * n;
      eval(arg, res, iw, w, 0);
      sink += out[0];
    }
    ++passes;
  }
  long reps = (long)ceil(2e-3 / (0.3 / passes));
  if (reps < 1) reps = 1;
  double ns[51];
  for (int k = 0; k < 51; ++k) {
    double a = now();
    for (long r = 0; r < reps; ++r)
      for (int s = 0; s < count; ++s) {
        const double* x = &states[4 * n * s];
        arg[0] = x, arg[1] = x + n, arg[2] = x + 2 * n;
        eval(arg, res, iw, w, 0);
        sink += out[0];
      }
    ns[k] = (now() - a) * 1e9 / ((double)reps * count);
  }
  qsort(ns, 51, sizeof(double), by_value);
  printf("%s: Pinocchio + CasADi generated C, `casadi_q_cse`: %g ns per call (median of 51), "
         "%d states, max relative error against tendyn %g (checksum %g)\n",
         argv[1], ns[25], count, worst, sink);
  free(states), free(arg), free(res), free(iw), free(w), free(out);
  return 0;
}
