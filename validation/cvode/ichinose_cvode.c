/*
 * The paper's example (models/ichinose1986.toml) solved by SUNDIALS CVODE, as a small C program
 * would solve it: the body's constants from book/src/model.md, eq. 16 in each mode, CVODE's BDF
 * at rtol = 1e-10 and atol = 1e-12 with a dense Jacobian, its root finding for the guards, the
 * resets applied and CVODE restarted after each event, and the samples every 5 ms written to a
 * CSV file with stdio (t, q, qdot, mode) with the event log. It serves the whole-process timing
 * in book/src/reference/exact-method.md (validation/cvode/README.md); nothing here is part of
 * flexrock.
 *
 *   cc -O2 -I<sundials>/include ichinose_cvode.c <sundials libs> -lm -o ichinose_cvode
 *   ./ichinose_cvode OUT_DIR
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

enum { PRE = 0, RIGHT = 1, LEFT = 2, OVER = 3 };
static const char *MODE_NAME[] = {"pre-uplift", "rock-right", "rock-left", "overturned"};

/* The body and the floor (the paper's example). */
static const double H = 4.0, B = 0.7, D = 1.0, RHO = 600.0, E = 5.0e6, DAMPING = 0.05, G = 9.81;
static const double AMPLITUDE = 5.0, PERIOD = 1.0, RAMP = 0.412, DURATION = 6.0, DT = 0.005;

struct Model {
  double me, ke, c, s_n, nu2, beta1, beta2, zeta_up, zeta_land;
  double ramp[3];
  int mode;
};

static void constants(struct Model *m) {
  const double lam = 1.875104068711961;
  const double sig = (cosh(lam) + cos(lam)) / (sinh(lam) + sin(lam));
  double mass = RHO * H * B * D, ei = E * D * B * B * B / 12.0;
  double int_u = sig / lam, int_u2 = 0.25;
  m->me = mass * int_u;
  m->ke = lam * lam * lam * sig * ei / (H * H * H);
  double omega = sqrt(m->ke / m->me);
  m->c = 2.0 * DAMPING / omega;
  m->beta1 = int_u / int_u2;
  m->s_n = B / (2.0 * ei * lam * lam / (mass * G * H * H) + 2.0 * sig / lam);
  double s = m->s_n, d = B - s;
  double int_uv = (-s / 4.0 + B / (lam * lam)) / d;
  double int_v = (-s * sig / lam + B / 2.0) / d;
  double int_v2 = (s * s / 4.0 - 2.0 * B * s / (lam * lam) + B * B / 3.0) / (d * d);
  m->nu2 = int_uv / int_v2;
  m->beta2 = int_v / int_v2;
  double int_uy = H * H / (lam * lam), int_vy = H * H * (B / 3.0 - s / (lam * lam)) / d;
  m->zeta_up = (int_uy + B * B / 12.0) / (int_vy + B * B / 12.0 + (B * B / 4.0) * B / d);
  m->zeta_land = (int_uy + B * B / 12.0) / (int_vy + B * B / 12.0 - (B * B / 4.0) * B / d);
  /* The ramp's cubic: a, floor velocity and displacement continuous with the sine at RAMP. */
  double w = 2.0 * M_PI / PERIOD, t = RAMP;
  double a[3][4] = {
      {t, t * t, t * t * t, AMPLITUDE * sin(w * t)},
      {t * t / 2, t * t * t / 3, t * t * t * t / 4, -(AMPLITUDE / w) * cos(w * t)},
      {t * t * t / 6, t * t * t * t / 12, t * t * t * t * t / 20, -(AMPLITUDE / (w * w)) * sin(w * t)},
  };
  for (int i = 0; i < 3; i++) { /* Gaussian elimination with partial pivoting */
    int p = i;
    for (int r = i + 1; r < 3; r++)
      if (fabs(a[r][i]) > fabs(a[p][i])) p = r;
    for (int k = 0; k < 4; k++) {
      double x = a[i][k];
      a[i][k] = a[p][k];
      a[p][k] = x;
    }
    for (int r = i + 1; r < 3; r++) {
      double f = a[r][i] / a[i][i];
      for (int k = i; k < 4; k++) a[r][k] -= f * a[i][k];
    }
  }
  for (int i = 2; i >= 0; i--) {
    double x = a[i][3];
    for (int k = i + 1; k < 3; k++) x -= a[i][k] * m->ramp[k];
    m->ramp[i] = x / a[i][i];
  }
}

static double floor_acceleration(const struct Model *m, double t, int before_ramp) {
  if (before_ramp) return t * (m->ramp[0] + t * (m->ramp[1] + t * m->ramp[2]));
  return AMPLITUDE * sin(2.0 * M_PI * t / PERIOD);
}

/* F, F' and nu, beta of the mode. */
static void mode_terms(const struct Model *m, double q, double *f, double *fp, double *nu,
                       double *beta) {
  if (m->mode == PRE) {
    *f = m->ke * q, *fp = m->ke, *nu = 1.0, *beta = m->beta1;
    return;
  }
  double slope = -m->ke * m->s_n / (B - m->s_n);
  *fp = slope, *nu = m->nu2, *beta = m->beta2;
  *f = m->mode == RIGHT ? m->ke * m->s_n * (B - q) / (B - m->s_n)
                        : -m->ke * m->s_n * (B + q) / (B - m->s_n);
}

struct Segment {
  struct Model *m;
  int before_ramp;
};

static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *data) {
  struct Segment *s = data;
  double q = NV_Ith_S(y, 0), v = NV_Ith_S(y, 1), f, fp, nu, beta;
  mode_terms(s->m, q, &f, &fp, &nu, &beta);
  NV_Ith_S(ydot, 0) = v;
  NV_Ith_S(ydot, 1) =
      (-beta * s->m->me * floor_acceleration(s->m, t, s->before_ramp) - s->m->c * nu * fp * v -
       nu * f) / s->m->me;
  return 0;
}

static int jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix j, void *data, N_Vector t1,
                    N_Vector t2, N_Vector t3) {
  struct Segment *s = data;
  double f, fp, nu, beta;
  mode_terms(s->m, 0.0, &f, &fp, &nu, &beta);
  SM_ELEMENT_D(j, 0, 0) = 0.0;
  SM_ELEMENT_D(j, 0, 1) = 1.0;
  SM_ELEMENT_D(j, 1, 0) = -nu * fp / s->m->me;
  SM_ELEMENT_D(j, 1, 1) = -s->m->c * nu * fp / s->m->me;
  return 0;
}

/* Guards: [0] q - level0, [1] q - level1, with the directions of the mode. */
static void guards(const struct Model *m, double level[2], int direction[2]) {
  switch (m->mode) {
  case PRE:
    level[0] = m->s_n, direction[0] = 1, level[1] = -m->s_n, direction[1] = -1;
    break;
  case RIGHT:
    level[0] = m->s_n, direction[0] = -1, level[1] = B, direction[1] = 1;
    break;
  default:
    level[0] = -m->s_n, direction[0] = 1, level[1] = -B, direction[1] = -1;
  }
}

static double LEVEL[2];
static int roots(sunrealtype t, N_Vector y, sunrealtype *g, void *data) {
  g[0] = NV_Ith_S(y, 0) - LEVEL[0];
  g[1] = NV_Ith_S(y, 0) - LEVEL[1];
  return 0;
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  struct Model m;
  memset(&m, 0, sizeof m);
  constants(&m);
  char path[4096];
  snprintf(path, sizeof path, "%s/history.csv", argv[1]);
  FILE *history = fopen(path, "w");
  snprintf(path, sizeof path, "%s/events.csv", argv[1]);
  FILE *events = fopen(path, "w");
  if (!history || !events) {
    perror(argv[1]);
    return 1;
  }
  fprintf(history, "t,q,qdot,mode\n");
  fprintf(events, "t,kind,from,to,q,qdot_before,qdot_after\n");

  SUNContext context;
  SUNContext_Create(NULL, &context);
  N_Vector y = N_VNew_Serial(2, context);
  SUNMatrix a = SUNDenseMatrix(2, 2, context);
  SUNLinearSolver ls = SUNLinSol_Dense(y, a, context);
  void *cvode = CVodeCreate(CV_BDF, context);
  NV_Ith_S(y, 0) = 0.0, NV_Ith_S(y, 1) = 0.0;
  struct Segment segment = {&m, 1};
  CVodeInit(cvode, rhs, 0.0, y);
  CVodeSStolerances(cvode, 1e-10, 1e-12);
  CVodeSetUserData(cvode, &segment);
  CVodeSetLinearSolver(cvode, ls, a);
  CVodeSetJacFn(cvode, jacobian);
  CVodeSetMaxNumSteps(cvode, 1000000);
  CVodeRootInit(cvode, 2, roots);
  int direction[2];
  guards(&m, LEVEL, direction);
  CVodeSetRootDirection(cvode, direction);
  CVodeSetStopTime(cvode, RAMP);

  long sample = 0, n_events = 0;
  double t = 0.0;
  fprintf(history, "%.17g,%.17g,%.17g,%s\n", 0.0, 0.0, 0.0, MODE_NAME[m.mode]);
  sample = 1;
  while (m.mode != OVER && sample * DT <= DURATION + 1e-12) {
    double target = sample * DT;
    int flag = CVode(cvode, target, y, &t, CV_NORMAL);
    if (flag < 0) {
      fprintf(stderr, "CVODE failed (%d) at t = %g\n", flag, t);
      return 1;
    }
    if (flag == CV_ROOT_RETURN) {
      int found[2];
      CVodeGetRootInfo(cvode, found);
      int which = found[0] ? 0 : 1;
      double before = NV_Ith_S(y, 1), after = before;
      int from = m.mode;
      const char *kind;
      if (m.mode == PRE) {
        kind = "uplift", m.mode = which == 0 ? RIGHT : LEFT, after = m.zeta_up * before;
      } else if (which == 0) {
        kind = "landing", m.mode = PRE, after = before / m.zeta_land;
      } else {
        kind = "overturn", m.mode = OVER;
      }
      NV_Ith_S(y, 0) = LEVEL[which], NV_Ith_S(y, 1) = after;
      fprintf(events, "%.17g,%s,%s,%s,%.17g,%.17g,%.17g\n", t, kind, MODE_NAME[from],
              MODE_NAME[m.mode], LEVEL[which], before, after);
      n_events++;
      if (m.mode == OVER) break;
      CVodeReInit(cvode, t, y);
      guards(&m, LEVEL, direction);
      CVodeSetRootDirection(cvode, direction);
      continue;
    }
    if (flag == CV_TSTOP_RETURN && segment.before_ramp && t < target) {
      /* The ramp's end: a kink of the floor motion; restart on the sine. */
      segment.before_ramp = 0;
      CVodeReInit(cvode, t, y);
      CVodeSetStopTime(cvode, DURATION);
      continue;
    }
    if (segment.before_ramp && t >= RAMP) {
      segment.before_ramp = 0;
      CVodeReInit(cvode, t, y);
      CVodeSetStopTime(cvode, DURATION);
    }
    fprintf(history, "%.17g,%.17g,%.17g,%s\n", t, NV_Ith_S(y, 0), NV_Ith_S(y, 1),
            MODE_NAME[m.mode]);
    sample++;
  }
  long steps = 0;
  CVodeGetNumSteps(cvode, &steps);
  fclose(history);
  fclose(events);
  printf("%ld events, %ld steps since the last restart, t = %.6f\n", n_events, steps, t);
  CVodeFree(&cvode);
  SUNLinSolFree(ls);
  SUNMatDestroy(a);
  N_VDestroy(y);
  SUNContext_Free(&context);
  return 0;
}
