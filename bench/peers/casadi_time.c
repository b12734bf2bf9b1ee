/* Times the C that CasADi generated from Pinocchio's RNEA (pinocchio_casadi.cpp: `casadi_q`
 * as the expression comes, `casadi_q_cse` after CasADi's common subexpression elimination),
 * each called through a pointer from this separately compiled file, with the protocol of
 * pinocchio_rnea.cpp: the states of NAME.states (the benchmark's 1,024 seeded states and
 * tendyn's Q at each), agreement with tendyn's Q first (max-norm relative error),
 * then 0.3 s of warm-up and the median ns per call of 51 samples of at least 2 ms. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

typedef double casadi_real;
typedef long long int casadi_int;
typedef int (*Eval)(const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w,
                    int mem);
typedef int (*Work)(casadi_int* sz_arg, casadi_int* sz_res, casadi_int* sz_iw, casadi_int* sz_w);
int casadi_q(const casadi_real**, casadi_real**, casadi_int*, casadi_real*, int);
int casadi_q_work(casadi_int*, casadi_int*, casadi_int*, casadi_int*);
int casadi_q_cse(const casadi_real**, casadi_real**, casadi_int*, casadi_real*, int);
int casadi_q_cse_work(casadi_int*, casadi_int*, casadi_int*, casadi_int*);

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int by_value(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

static void time_one(const char* name, Eval eval, Work work, const char* file, int n, int count,
                     const double* states) {
  casadi_int sz_arg, sz_res, sz_iw, sz_w;
  work(&sz_arg, &sz_res, &sz_iw, &sz_w);
  casadi_real* w = malloc(sizeof(casadi_real) * (sz_w + 1));
  casadi_int* iw = malloc(sizeof(casadi_int) * (sz_iw + 1));
  double* out = malloc(sizeof(double) * n);
  const casadi_real* arg[3];
  casadi_real* res[1] = {out};
  double worst = 0, sink = 0;
  for (int s = 0; s < count; ++s) {
    const double* x = &states[4 * n * s];
    arg[0] = x, arg[1] = x + n, arg[2] = x + 2 * n;
    eval(arg, res, iw, w, 0);
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
  printf("%s: Pinocchio + CasADi generated C, `%s`: %g ns per call (median of 51), %d states, "
         "max relative error against tendyn %g (checksum %g)\n",
         file, name, ns[25], count, worst, sink);
  free(w), free(iw), free(out);
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: casadi_time NAME.states\n");
    return 2;
  }
  FILE* in = fopen(argv[1], "r");
  int n, count = 0, capacity = 2048;
  if (!in || fscanf(in, "%d", &n) != 1) return 2;
  double* states = malloc(sizeof(double) * 4 * n * capacity);
  for (; count < capacity; ++count) {
    int i = 0;
    while (i < 4 * n && fscanf(in, "%lf", &states[4 * n * count + i]) == 1) ++i;
    if (i < 4 * n) break;
  }
  time_one("casadi_q", casadi_q, casadi_q_work, argv[1], n, count, states);
  time_one("casadi_q_cse", casadi_q_cse, casadi_q_cse_work, argv[1], n, count, states);
  return 0;
}
