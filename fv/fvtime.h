/*
** fvtime.h: the time loop of a solver in OpenFOAM's rules: the time step
** from the Courant number (adjustTimeStep, maxCo, maxDeltaT), time steps
** shortened to land on write times (writeControl adjustableRunTime with
** adjustTimeStep on; a fixed step is never changed, as in OpenFOAM), when
** to write (timeStep, runTime, adjustableRunTime, cpuTime, clockTime), and
** when to stop (endTime, stopAt).  Pure arithmetic on a Control
** (common/runtime.h): the frame does the printing, the solver the physics.
**
** OpenFOAM's formulas, so that a case behaves as its users expect:
**   setDeltaT:  f = maxCo / Co;  dt <- min(min(f, 1 + 0.1 f, 1.2) dt, maxDeltaT)
**   adjustDeltaT (adjustableRunTime, adjustTimeStep on): the steps left to the next write
**     time are rounded up and dt shared among them, changing by at most
**     a factor 2 up and 5 down;
**   a write happens when the time passes the next multiple of
**   writeInterval after startTime (runTime, adjustableRunTime), every
**   writeInterval steps (timeStep), or every writeInterval seconds of CPU
**   or wall-clock time since the start (cpuTime, clockTime).
*/
#ifndef KIESEL_FVTIME_H
#define KIESEL_FVTIME_H

#include "runtime.h"

typedef struct TimeLoop {
    const Control *c;
    double start;      /* startTime of the run */
    double value;      /* the current time */
    double dt, dt0;    /* this step's and the last step's */
    long index;        /* time steps since time 0 (uniform/time's index) */
    long write_index;  /* writes since the start (run- and clock-time controls) */
    int write_now;     /* the step just taken ends at a write time */
    int stop_now;      /* stopAt writeNow / noWriteNow / nextWrite acted on */
} TimeLoop;

/* Starts at time start (index steps done before it) with step dt. */
void timeloop_init(TimeLoop *t, const Control *c, double start, long index, double dt);

/* The next step from the Courant number co of the last one (adjustTimeStep
   on; without it dt stays controlDict's deltaT).  co <= 0 (a fluid at
   rest) grows dt by the largest factor, 1.2, as OpenFOAM's SMALL does. */
void timeloop_courant(TimeLoop *t, double co);

/* Is there a step to take (time below endTime by more than half a step,
   and no stop requested)? */
int timeloop_running(const TimeLoop *t);

/* Takes the step: shortens dt onto the next write time (adjustableRunTime
   with adjustTimeStep on),
   advances time and index, and sets write_now; elapsed is the CPU or wall
   time since the start in seconds, for cpuTime/clockTime writes (0
   otherwise). */
void timeloop_advance(TimeLoop *t, double elapsed);

/* Re-reads the write and stop settings after controlDict changed
   (runTimeModifiable): the next write time is recomputed from the new
   writeInterval, and stopAt writeNow ends the run after this step. */
void timeloop_control_changed(TimeLoop *t);

#endif
