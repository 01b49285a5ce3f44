/*
** test_fvtime.c: the time loop (fv/fvtime.h) against OpenFOAM's rules:
** adjustable write times hit exactly, the Courant-number step control,
** timeStep and runTime writes, stopAt nextWrite, the end time.
*/
#include "fvtime.h"
#include "test.h"

#include <math.h>
#include <string.h>

static Control control(int wc, double interval, double end, int adjust, double maxco, double maxdt)
{
    Control c;
    memset(&c, 0, sizeof c);
    c.writeControl = wc;
    c.writeInterval = interval;
    c.endTime = end;
    c.adjustTimeStep = adjust;
    c.maxCo = maxco;
    c.maxDeltaT = maxdt;
    c.stopAt = STOP_END;
    return c;
}

/* adjustableRunTime with a step that does not divide the interval: every
   write lands on a multiple of 0.1 to round-off, and the run ends at 1. */
TEST(adjustable_writes)
{
    Control c = control(WRITE_ADJUSTABLE, 0.1, 1.0, 1, 0.5, 1e15);
    TimeLoop t;
    timeloop_init(&t, &c, 0, 0, 0.03);
    int nw = 0, steps = 0;
    double worst = 0;
    while (timeloop_running(&t)) {
        timeloop_courant(&t, 0.5 * t.dt / 0.03); /* Co proportional to dt: dt stays near 0.03 */
        timeloop_advance(&t, 0);
        steps++;
        if (t.write_now) {
            nw++;
            worst = fmax(worst, fabs(t.value - 0.1 * nw));
        }
    }
    printf("  %d steps, %d writes, worst write time off by %.2e, end %.17g\n", steps, nw, worst, t.value);
    EXPECT(nw == 10, "%d writes", nw);
    EXPECT(worst < 1e-12, "write times off by %.3e", worst);
    NEAR(t.value, 1.0, 1e-12);
    EXPECT(steps >= 34 && steps <= 40, "%d steps for dt about 0.03", steps);
}

/* adjustableRunTime with adjustTimeStep off: the step stays deltaT (OpenFOAM
   fits steps to write times only when they adapt); a write comes with
   the first step past each multiple of 0.1. */
TEST(adjustable_fixed_step)
{
    Control c = control(WRITE_ADJUSTABLE, 0.1, 1.0, 0, 0.5, 1e15);
    TimeLoop t;
    timeloop_init(&t, &c, 0, 0, 0.03);
    int nw = 0, steps = 0;
    while (timeloop_running(&t)) {
        timeloop_advance(&t, 0);
        steps++;
        EXPECT(t.dt == 0.03, "step %d: dt %.17g", steps, t.dt);
        nw += t.write_now;
    }
    EXPECT(steps == 33, "%d steps", steps);
    EXPECT(nw == 10, "%d writes", nw);
}

/* setDeltaT: Co = 0 grows dt by 1.2 a step up to maxDeltaT; Co = 2 maxCo
   takes f = 0.5, so dt halves. */
TEST(courant_control)
{
    Control c = control(WRITE_TIMESTEP, 1000, 1e9, 1, 0.25, 1.0);
    TimeLoop t;
    timeloop_init(&t, &c, 0, 0, 0.1);
    timeloop_courant(&t, 0);
    NEAR(t.dt, 0.12, 1e-15);
    for (int i = 0; i < 50; i++) timeloop_courant(&t, 0);
    NEAR(t.dt, 1.0, 0);
    timeloop_courant(&t, 0.5);
    NEAR(t.dt, 0.5, 1e-14);
    /* f = 1.25: the growth limit 1 + 0.1 f = 1.125 applies */
    timeloop_courant(&t, 0.2);
    NEAR(t.dt, 0.5 * 1.125, 1e-14);
    Control fixed = control(WRITE_TIMESTEP, 1, 1, 0, 0.25, 1.0);
    timeloop_init(&t, &fixed, 0, 0, 0.1);
    timeloop_courant(&t, 100);
    NEAR(t.dt, 0.1, 0);
}

TEST(timestep_writes)
{
    Control c = control(WRITE_TIMESTEP, 5, 1.0, 0, 1, 1);
    TimeLoop t;
    timeloop_init(&t, &c, 0, 0, 0.01);
    int nw = 0, steps = 0;
    while (timeloop_running(&t)) {
        timeloop_advance(&t, 0);
        steps++;
        nw += t.write_now;
        if (t.write_now && steps % 5) EXPECT(0, "write at step %d", steps);
    }
    EXPECT(steps == 100 && nw == 20, "%d steps, %d writes", steps, nw);
}

/* runTime: the write comes with the first step past each multiple. */
TEST(runtime_writes)
{
    Control c = control(WRITE_RUNTIME, 0.25, 1.0, 0, 1, 1);
    TimeLoop t;
    timeloop_init(&t, &c, 2.0, 40, 0.1);
    c.endTime = 3.0;
    int nw = 0;
    double at[8];
    while (timeloop_running(&t)) {
        timeloop_advance(&t, 0);
        if (t.write_now && nw < 8) at[nw++] = t.value;
    }
    EXPECT(nw == 4, "%d writes", nw);
    NEAR(at[0], 2.3, 1e-12);
    NEAR(at[1], 2.5, 1e-12);
    NEAR(at[2], 2.8, 1e-12);
    NEAR(at[3], 3.0, 1e-12);
    EXPECT(t.index == 50, "index %ld", t.index);
}

TEST(stop_next_write)
{
    Control c = control(WRITE_TIMESTEP, 3, 1.0, 0, 1, 1);
    c.stopAt = STOP_NEXTWRITE;
    TimeLoop t;
    timeloop_init(&t, &c, 0, 0, 0.01);
    int steps = 0;
    while (timeloop_running(&t)) {
        timeloop_advance(&t, 0);
        steps++;
    }
    EXPECT(steps == 3 && t.write_now, "stopped after %d steps", steps);
    c.stopAt = STOP_WRITENOW;
    timeloop_init(&t, &c, 0, 0, 0.01);
    timeloop_advance(&t, 0);
    timeloop_control_changed(&t);
    EXPECT(t.write_now && !timeloop_running(&t), "writeNow: write and stop");
}

int main(void)
{
    RUN(adjustable_writes);
    RUN(adjustable_fixed_step);
    RUN(courant_control);
    RUN(timestep_writes);
    RUN(runtime_writes);
    RUN(stop_next_write);
    return test_summary();
}
