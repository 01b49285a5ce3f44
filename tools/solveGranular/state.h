/*
** state.h: solveGranular's time directories: where a run starts (the
** controlDict's startFrom/startTime, and uniform/time for the exact time
** value, the step index and the step size, so that a restart from binary
** output continues the uninterrupted run bit for bit) and what a write
** time holds (rho, U, the derived p, uniform/time), written atomically,
** field by field, uniform/time last, then purgeWrite, then (controlDict's
** writeVTK, default yes) the VTK files writeVTK would write, VTK/ kept a
** mirror of the time directories left (common/vtkcase.h, vtkcase_sync).
*/
#ifndef KIESEL_STATE_H
#define KIESEL_STATE_H

#include "buf.h"
#include "case.h"
#include "field.h"
#include "mesh.h"

typedef struct Start {
    char name[64];   /* the time directory */
    double value;    /* uniform/time's value, else the name's */
    long index;      /* steps before it (uniform/time; 0 without) */
    double dt;       /* uniform/time's deltaT, else controlDict's */
} Start;

/* The start time of the case (case_pick_times without a selection). */
int state_start(Case *c, Start *s, Err *e);

/* Reads field name of width width (1 volScalarField, 3 volVectorField)
   from time directory time. */
int state_read_field(Field *f, const Mesh *m, const Case *c, const char *time, const char *name, int width,
                     Err *e);

/* Writes the fields (n of them) and uniform/time at time t, then purges
   old times (purgeWrite), then state_write_vtk; the time's name into name
   (64 bytes), the VTK line into log. */
int state_write(const Case *c, const Mesh *m, Field *const *f, int n, double t, long index, double dt, double dt0,
                char *name, Buf *log, Err *e);
/* With controlDict's writeVTK on: the VTK files of time directory name
   and the series (vtkcase_sync; the start time's at the start of a run,
   so that the series begins there); one line into log. */
int state_write_vtk(const Case *c, const Mesh *m, const char *name, Buf *log, Err *e);

#endif
