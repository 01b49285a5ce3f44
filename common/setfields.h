/*
** setfields.h: setFieldsDict: default values and regions, parsed into
** solids (geometry.h, the primitives geometryDict uses) with the values
** they set, and applied to the vol fields of a time directory.
**
**   defaultFieldValues ( volScalarFieldValue alpha.s 0 ... );
**   regions ( sphereToCell { centre (..); radius ..; fieldValues (..); }
**             shapeToCell { shape difference; a { shape box; ... }
**                           b { shape sphere; ... } fieldValues (..); } ... );
**
** Every cell first gets the default values; then each region, in order,
** blends its values in with the cell's volume fraction f inside the shape:
** v = (1 - f) v + f v_region (`fractional no;` uses OpenFOAM's rule: f = 1
** when the cell centre is inside, else 0); f is volfrac.h's.
**
** The whole dictionary is checked and every field read before anything is
** written, and each field file is replaced atomically, so a bad dictionary
** or a missing field leaves the case untouched.  Progress text goes into a
** Buf for the tool to print: the library never prints.
*/
#ifndef KIESEL_SETFIELDS_H
#define KIESEL_SETFIELDS_H

#include "buf.h"
#include "dict.h"
#include "err.h"
#include "field.h"
#include "mesh.h"
#include "geometry.h"

/* One "volScalarFieldValue NAME value" item. */
typedef struct SetValue {
    const char *name;  /* lives as long as the dictionary */
    int width;         /* 1 or 3 */
    double v[3];
    int field;         /* index into SetFields.fields */
    const char *file;
    int line;
} SetValue;

typedef struct SetRegion {
    const char *type;  /* "sphereToCell" */
    Geometry solid;    /* one surface, flow inside */
    int centred;       /* 2-D: cut through centre, not the mesh's mid-plane */
    double centre[3];
    int fractional;
    SetValue *vals;
    int nvals;
    const char *file;
    int line;
} SetRegion;

typedef struct SetFields {
    SetValue *defaults;
    int ndefaults;
    SetRegion *regions;
    int nregions;
    const char **fields;   /* distinct field names in order of first use */
    int *widths;
    const char **field_file;  /* where each field is first set */
    int *field_line;
    int nfields;
} SetFields;

/* Top-level keywords and the help text on region types, for -help. */
extern const DictKey setfields_keys[];
extern const char setfields_help[];

/* Parses and checks the whole dictionary (s need not be initialised; it
   is always safe to setfields_free afterwards).  Names point into d;
   file names in shapeToCell regions (stl, cad) are relative to case_dir
   (NULL: the working directory). */
int setfields_parse(SetFields *s, const Dict *d, const char *case_dir, Err *e);
void setfields_free(SetFields *s);

/* Fits the solids to the mesh (with geometry): on a 2-D mesh (one cell
   thick between empty patches) each solid is replaced by its section
   through its centre (shapeToCell: through the mesh's mid-plane),
   extruded (geometry_flatten), so spheres and cylinders along the empty
   axis set discs.  Appends the "Mesh: ..." report. */
void setfields_on_mesh(SetFields *s, const Mesh *m, Buf *log);

/* Reads the fields of <case_dir>/<time>, sets the defaults and regions
   and writes the fields back (o->location is replaced by time), appending
   the progress report to log and the fields' warnings (Field.warn: a
   boundaryField entry naming no patch, ...) to warn, one per line, for
   the tool to print.  What the fields hold beyond what is set (other
   entries, unknown patch entries) is written back as read. */
int setfields_time(const SetFields *s, const Mesh *m, const char *case_dir, const char *time,
                   const FieldWriteOpts *o, Buf *log, Buf *warn, Err *e);

#endif
