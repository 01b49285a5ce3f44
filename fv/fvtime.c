/*
** fvtime.c: the time loop in OpenFOAM's rules (fvtime.h).
*/
#include "fvtime.h"

#include <math.h>

#define SMALL 1e-15

void timeloop_init(TimeLoop *t, const Control *c, double start, long index, double dt)
{
    t->c = c;
    t->start = t->value = start;
    t->dt = t->dt0 = dt;
    t->index = index;
    t->write_index = 0;
    t->write_now = 0;
    t->stop_now = 0;
}

void timeloop_courant(TimeLoop *t, double co)
{
    if (!t->c->adjustTimeStep) return;
    double f = t->c->maxCo / (fmax(co, 0) + SMALL);
    double g = fmin(fmin(f, 1 + 0.1 * f), 1.2);
    t->dt = fmin(g * t->dt, t->c->maxDeltaT);
}

int timeloop_running(const TimeLoop *t)
{
    if (t->stop_now) return 0;
    return t->value < t->c->endTime - 0.5 * t->dt;
}

/* adjustableRunTime: the steps to the next write time, rounded up, share
   the time left (OpenFOAM's Time::adjustDeltaT). */
static void adjust_to_write(TimeLoop *t)
{
    double w = t->c->writeInterval;
    if (!(w > 0)) return;
    double left = fmax(0, (double)(t->write_index + 1) * w - (t->value - t->start));
    double n = left / t->dt - SMALL;
    if (!(n < 2e9)) return;
    double dt = left / (floor(n) + 1);
    t->dt = dt >= t->dt ? fmin(dt, 2 * t->dt) : fmax(dt, 0.2 * t->dt);
}

static int write_due(TimeLoop *t, double elapsed)
{
    const Control *c = t->c;
    double w = c->writeInterval;
    switch (c->writeControl) {
    case WRITE_TIMESTEP:
        return w >= 1 && t->index % (long)w == 0;
    case WRITE_RUNTIME:
    case WRITE_ADJUSTABLE: {
        /* the index of the write interval the time is in, with room for
           round-off of the summed steps */
        long k = (long)floor((t->value - t->start) / w + 1e-9);
        if (k > t->write_index) {
            t->write_index = k;
            return 1;
        }
        return 0;
    }
    default: {
        long k = (long)floor(elapsed / w);
        if (k > t->write_index) {
            t->write_index = k;
            return 1;
        }
        return 0;
    }
    }
}

void timeloop_advance(TimeLoop *t, double elapsed)
{
    /* as OpenFOAM, only a step that adapts is fitted to the write times */
    if (t->c->adjustTimeStep && t->c->writeControl == WRITE_ADJUSTABLE) adjust_to_write(t);
    t->dt0 = t->dt;
    t->value += t->dt;
    t->index++;
    t->write_now = write_due(t, elapsed);
    /* the last step writes, as OpenFOAM's Time at endTime */
    if (!timeloop_running(t)) t->write_now = 1;
    if (t->c->stopAt == STOP_NEXTWRITE && t->write_now) t->stop_now = 1;
}

void timeloop_control_changed(TimeLoop *t)
{
    const Control *c = t->c;
    if (c->writeControl == WRITE_RUNTIME || c->writeControl == WRITE_ADJUSTABLE)
        t->write_index = (long)floor((t->value - t->start) / c->writeInterval + 1e-9);
    if (c->stopAt == STOP_WRITENOW) t->write_now = t->stop_now = 1;
    else if (c->stopAt == STOP_NOWRITENOW) t->stop_now = 1;
}
