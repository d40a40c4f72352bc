/* The FFTW baseline of the field benchmark: the time FFTW takes for the transforms of the
 * paper's §3.3 synthesis done the plain way, three complex single-precision 4-D inverse
 * transforms (one per velocity component) of an n^4 lattice.
 *
 * Plans with FFTW_MEASURE (planning is not timed), transforms in place, and prints one JSON
 * line per lattice: {"name": "fftw_inverse_3x_c2c_NxNxNxN_ms", "value": median ms, "unit": "ms"}.
 * Built and run by scripts/bench.mjs when Debian's libfftw3-dev is installed:
 *   gcc -O2 -o fftw-baseline scripts/fftw-baseline.c -lfftw3f -lm && ./fftw-baseline 32 64
 */
#include <fftw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now_ms(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static int by_value(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Median wall time in ms of `runs` rounds (after one warm-up) of three inverse transforms. */
static double time_lattice(int n, int runs) {
  int dims[4] = {n, n, n, n};
  size_t points = (size_t)n * n * n * n;
  fftwf_complex *u[3];
  for (int c = 0; c < 3; c++) u[c] = fftwf_malloc(sizeof(fftwf_complex) * points);
  fftwf_plan plan = fftwf_plan_dft(4, dims, u[0], u[0], FFTW_BACKWARD, FFTW_MEASURE);
  /* A fixed pseudo-random spectrum (planning overwrote the buffers). */
  unsigned s = 12345;
  for (int c = 0; c < 3; c++) {
    for (size_t i = 0; i < points; i++) {
      s = s * 1664525u + 1013904223u;
      u[c][i][0] = (float)(s >> 8) / 16777216.0f - 0.5f;
      s = s * 1664525u + 1013904223u;
      u[c][i][1] = (float)(s >> 8) / 16777216.0f - 0.5f;
    }
  }
  double *t = malloc(sizeof(double) * runs);
  for (int r = -1; r < runs; r++) {
    double start = now_ms();
    for (int c = 0; c < 3; c++) fftwf_execute_dft(plan, u[c], u[c]);
    if (r >= 0) t[r] = now_ms() - start;
  }
  qsort(t, runs, sizeof(double), by_value);
  double median = t[runs / 2];
  free(t);
  fftwf_destroy_plan(plan);
  for (int c = 0; c < 3; c++) fftwf_free(u[c]);
  return median;
}

int main(int argc, char **argv) {
  for (int a = 1; a < argc; a++) {
    int n = atoi(argv[a]);
    if (n < 2) {
      fprintf(stderr, "fftw-baseline: bad lattice extent \"%s\"\n", argv[a]);
      return 2;
    }
    double ms = time_lattice(n, n >= 64 ? 5 : 9);
    printf("{\"name\":\"fftw_inverse_3x_c2c_%dx%dx%dx%d_ms\",\"value\":%.3f,\"unit\":\"ms\"}\n", n, n, n,
           n, ms);
    fflush(stdout);
  }
  return 0;
}
