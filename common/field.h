/*
** field.h: volume fields (volScalarField, volVectorField) with their
** boundary conditions, read from and written to time directories.
**
** A Field holds one value (width 1) or one vector (width 3) per cell in
** a flat array, and one PatchField per mesh patch.  A PatchField keeps its
** type and, where the type has one, its face values; every other entry of
** its dictionary (inletValue, phi, ...) is kept verbatim in `extra` so that
** a tool that only changes the internal field (setFields) writes back
** exactly the boundary conditions it read, even of types it does not know.
**
** Basic types understood here: fixedValue (value required), zeroGradient,
** calculated, slip, noSlip, empty, cyclic, symmetry, symmetryPlane.  Patch
** entries in boundaryField are found as OpenFOAM's readField finds them:
** by name, then by group ("wall" matches patches of type wall or with wall
** in their inGroups; the last group entry wins), then by regex key (".*",
** "(left|right)"; the last match wins).  Every mesh patch must be covered,
** except that a patch of a constraint type (empty, cyclic, symmetry,
** symmetryPlane, wedge) without an entry by name or group takes that type.
*/
#ifndef KIESEL_FIELD_H
#define KIESEL_FIELD_H

#include "dict.h"
#include "err.h"
#include "mesh.h"

typedef struct PatchField {
    char *type;
    int n;             /* face count of the patch */
    double *value;     /* n*width face values, or NULL when the type has none */
    Dict *extra;       /* other entries, written back verbatim (may be NULL) */
    char *file;        /* where its boundaryField entry is (field_read; the */
    int line;          /* field's file and line 0 when the patch took its
                          constraint type without an entry; NULL and 0 from
                          field_init), for the solvers' messages */
} PatchField;

/* Places of the kept top-level entries: before dimensions, before
   internalField, before boundaryField, after boundaryField. */
enum { FIELD_NKEEP = 4 };

typedef struct Field {
    char *name;
    int width;         /* 1 scalar, 3 vector */
    double dims[7];    /* [kg m s K mol A cd] exponents */
    int ncells;
    double *v;         /* ncells*width */
    int npatches;
    PatchField *pf;    /* one per mesh patch, in mesh order */
    /* What field_read does not interpret, written back by field_write so
       that a rewrite loses nothing: the other top-level entries (user
       entries, values that came from #include), by place (keep[k] goes
       before the k-th of dimensions, internalField, boundaryField, or
       after them for k = 3), and the boundaryField entries no patch took
       (a name that is no patch of the mesh, a group or regex entry that
       every patch it matches overrides), written after the patches.  NULL
       when there are none. */
    Dict *keep[FIELD_NKEEP];
    Dict *keep_bf;
    /* "file:line: ..." warnings for the tool to print (err_warn): a
       boundaryField entry that names no patch or group of the mesh,
       directives the dictionary reader ignored. */
    char **warn;
    int nwarn;
} Field;

typedef struct FieldWriteOpts {
    int binary;
    int gzip;
    int precision;     /* ascii significant digits; <= 0 = shortest exact */
    const char *location;  /* time name for the header, or NULL */
} FieldWriteOpts;

/* A new field with a uniform value (width numbers) and every patch set to
   the given default type ("zeroGradient", "calculated", ...); patches of
   a constraint type (empty, cyclic, symmetry, symmetryPlane, wedge) get
   that type, as OpenFOAM requires.  Types with a value (fixedValue,
   calculated) get the uniform value on their faces. */
void field_init(Field *f, const Mesh *m, const char *name, int width, const double *uniform,
                const char *default_type);
void field_free(Field *f);

/* The `dimensions` entry of d: 7 (or 5) exponents [kg m s K mol A cd], or
   unit words ([m s^-1]); the message names file and line. */
int field_read_dims(const Dict *d, const char *file, double dims[7], Err *e);

/* Reads <path> (or path.gz): class must be volScalarField or
   volVectorField; internalField uniform or nonuniform with the right
   count; a boundaryField entry for every patch.  NaN or Inf values are
   refused with the file and the first offending index (and, when written
   as words, their own line and text).  Entries it does not interpret are
   kept (keep, keep_bf) and warnings collected (warn), see Field. */
int field_read(Field *f, const Mesh *m, const char *path, Err *e);
/* Class of a field file without reading its data: returns width (1 or 3),
   0 when the file is not a vol field, -1 on error. */
int field_probe(const char *path, char **cls, Err *e);
/* Writes atomically. */
int field_write(const Field *f, const Mesh *m, const char *path, const FieldWriteOpts *o, Err *e);

/* Face values on patch p (n*width numbers into out) as the boundary
   condition gives them from the current internal field: fixedValue and
   calculated -> value; zeroGradient, empty, unknown -> owner cell value;
   slip/symmetry -> owner value without its normal component (vectors);
   noSlip -> 0; cyclic -> average of owner and the cyclic partner's cell. */
void field_patch_values(const Field *f, const Mesh *m, int p, double *out);

/* What a patch type means (field_bc.c): it holds face values that are
   part of the condition (fixedValue, calculated); it is understood here
   and holds none (zeroGradient, slip, noSlip, empty, cyclic, symmetry,
   symmetryPlane); it is a constraint type, which a mesh patch of that
   type forces on its patch field (empty, cyclic, symmetry, symmetryPlane,
   wedge).  NULL is none of them. */
int field_type_needs_value(const char *type);
int field_type_valueless(const char *type);
int field_type_constraint(const char *type);

/* Cell index of the first non-finite internal value, or -1. */
long field_first_nonfinite(const Field *f);

/* ---- the fields of a time directory (field_time.c) ---- */

/* "<case_dir>/<time>/<name>" (caller frees). */
char *field_time_path(const char *case_dir, const char *time, const char *name);
/* Reads field `name` of time directory <case_dir>/<time> (or its .gz).
   Returns 0, or -1 with e filled; returns 1 without touching e when the
   file does not exist, so that the caller can name the dictionary entry
   that asked for it.  *path (if path is not NULL) receives the file name
   either way (caller frees). */
int field_read_time(Field *f, const Mesh *m, const char *case_dir, const char *time, const char *name, char **path,
                    Err *e);
/* Reads the vol fields of directory dir in name order into a new array
   *out: all of them (nwant 0) or those named in want; files of other
   classes are skipped, except that a wanted one is an error.  Returns the
   count or -1 (nothing allocated). */
int field_read_dir(const Mesh *m, const char *dir, const char *const *want, int nwant, Field **out, Err *e);
/* The vol fields of directory dir as field_read_dir would read them,
   without reading their data: their names and paths into new arrays
   (io_free_list frees each).  Returns the count or -1. */
int field_list_dir(const char *dir, const char *const *want, int nwant, char ***names, char ***paths, Err *e);
/* Frees n fields and the array (f may be NULL; zeroed entries are fine). */
void field_free_all(Field *f, int n);

#endif
