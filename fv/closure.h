/*
** closure.h: the granular closures of thesis ch. 2 (eq. 2.15-2.29) as
** pure functions of the volume fraction c and the granular temperature T,
** and the homogeneous cooling they imply (a reference for the solver's
** tests).
**
**   g      = 1/(1 - c/c_max)                            eq. 2.15
**   p_k    = c g T,  p_y = Theta(c - c0) T0 (c - c0) g  eq. 2.20, 2.26
**   eta    = eta0 g (c sqrt T + Y/sqrt T)               eq. 2.21, 2.27
**   lambda = lambda0 g (c sqrt T + Y/sqrt T)            eq. 2.22, 2.28
**   eps    = eps0 g (sqrt T + Y/(c sqrt T))             eq. 2.23, 2.29 (*)
**   with Y = Theta(c - c0) T0 (c - c0) = p_y/g
**
** These are eta_k (1 + p_y/p_k) and its kin written so that no 0/0 is
** ever formed.  (*) eps is eps_k (1 + p_y/p_k), the multiplicative form;
** the closed form printed as eq. 2.29 lacks the factor 1/c (spec §1.3 [?]).
**
** Domain (not checked; outside it the values are not meaningful):
** 0 <= c < c_max, 0 <= c0, T0 >= 0, and T >= 0 where there is no yield
** (c <= c0 or T0 = 0), T > 0 where there is (eta, lambda and eps diverge
** like 1/sqrt T; the solver clamps T >= T_min).  p and dp/dc are finite
** for every T >= 0.  At c = c0 exactly the yield terms vanish and dp/dc
** takes its larger, right-hand value (see closure.c).
*/
#ifndef KIESEL_CLOSURE_H
#define KIESEL_CLOSURE_H

#include "err.h"

typedef struct GranCoeffs {
    double eta0, lambda0, eps0;  /* eq. 2.21-2.23 [m, m, 1/m] */
    double cmax, c0, T0;         /* c_max, yield onset c0, yield temperature T0 [m^2/s^2] (eq. 2.26-2.29) */
    double KT;                   /* heating-and-conduction factor, default 2/3 (spec correction 1) */
} GranCoeffs;

typedef struct GranClosure {
    double g;                 /* eq. 2.15: 1/(1 - c/cmax) */
    double pk, py, p;         /* eq. 2.20, yield pressure (eq. 2.26), p = pk + py (eq. 2.16) */
    double eta, lambda, eps;  /* eta = eta_k (1 + py/pk) etc., in closed forms */
    double dpdc;              /* dp/dc at fixed T (for the acoustic speed sqrt(dpdc)) */
} GranClosure;

/* Every closure at (c, T) at once. */
void closure_eval(const GranCoeffs *k, double c, double T, GranClosure *out);

/* The closures one at a time (the same numbers as closure_eval's). */
double closure_pressure(const GranCoeffs *k, double c, double T);
double closure_eta(const GranCoeffs *k, double c, double T);
double closure_lambda(const GranCoeffs *k, double c, double T);
double closure_eps(const GranCoeffs *k, double c, double T);
/* sqrt(dp/dc) at fixed T. */
double closure_sound_speed(const GranCoeffs *k, double c, double T);

/* The rest profile at fixed T (doc/theory.md, "Well-balanced granular
   gravity").  At rest grad p = c g, so the enthalpy h = int dp/c grows by
   the potential g.dx.  In the logit v = ln(c/(c_max - c)) (so c = c_max
   e^v/(1 + e^v), g = 1 + e^v) with s(v) = v + e^v and B = T0 (1 - c0/c_max):
     p = c_max [(T + B) e^v - T0 c0/c_max]  above c0, c_max T e^v below,
     h = T s(v) + B (s(v) - s(v0)) above c0 (v0 the logit of c0), T s(v)
         below,
   both monotone in v, so the profile through (v, T) has the logit
   closure_profile_logit at potential difference phi: the inverse of s
   by Newton's method from a start that depends on s only (two sources
   whose profiles coincide give the same bits to round-off).  -INFINITY
   is the logit of c = 0 (an empty cell's profile stays empty). */
double closure_logit(const GranCoeffs *k, double c);
double closure_c_of_logit(const GranCoeffs *k, double v);
double closure_pressure_logit(const GranCoeffs *k, double v, double T);
/* The logit of the pressure p >= 0 at temperature T > 0 (its inverse). */
double closure_logit_of_pressure(const GranCoeffs *k, double p, double T);
/* The logit at potential difference phi along the rest profile through
   logit v at temperature T (T > 0, or T = 0 above c0). */
double closure_profile_logit(const GranCoeffs *k, double v, double T, double phi);
/* dp/dc at fixed T from the logit: (1 + e^v)^2 (T + B above c0). */
double closure_dpdc_logit(const GranCoeffs *k, double v, double T);

/* eq. 2.24: eps0 of grains of diameter d and restitution e (0 <= e <= 1);
   0 for e = 1 (elastic grains do not cool). */
double closure_eps0_from_grain(double d, double e);
/* eq. 2.25: the internal friction angle atan(sqrt(eps0 eta0)) [rad]. */
double closure_friction_angle(double eps0, double eta0);

/* Homogeneous cooling (uniform c, u = 0): dT/dt = -eps(c, T) T from
   T(0) = Tinit.  closure_cooling_exact is the closed form: without yield
   Tinit / (1 + eps0 g sqrt(Tinit) t / 2)^2; with yield the solution of
   d(sqrt T)/dt = -(eps0 g / 2)(T + b), b = T0 (c - c0)/c, which reaches
   T = 0 at a finite time and stays there (closure.c).  closure_cooling_ode
   integrates the ODE through closure_eps with GSL (rk8pd, relative
   tolerance 1e-12), for either regime; it returns 0 with *T set, or -1
   with e filled when the input is outside the domain or GSL fails. */
double closure_cooling_exact(const GranCoeffs *k, double c, double Tinit, double t);
int closure_cooling_ode(const GranCoeffs *k, double c, double Tinit, double t, double *T, Err *e);

#endif
