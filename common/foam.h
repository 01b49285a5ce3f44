/*
** foam.h: writing OpenFOAM files: the banner, the FoamFile header, and
** numeric lists in ascii or binary, plus the number formatting and fast
** number parsing that the dictionary reader shares.
**
** Ascii numbers: foam_fmt_double writes the shortest decimal that reads
** back to the same double (tries 15, 16, then 17 significant digits), so
** an ascii -> binary -> ascii round trip is bit-exact and grid points stay
** readable (0.005, not 0.0050000000000000001).  A precision p > 0 writes
** "%.{p}g" instead (OpenFOAM's writePrecision).
** Binary lists: "N\n(" raw little-endian bytes ")", labels as int32 and
** scalars as float64 ("arch "LSB;label=32;scalar=64""), as OpenFOAM.
*/
#ifndef KIESEL_FOAM_H
#define KIESEL_FOAM_H

#include <stddef.h>

#include "buf.h"

/* Header for a file of the given class and object.  location may be NULL
   (written as location "0.5"; when given).  note may be NULL. */
void foam_header(Buf *b, const char *cls, const char *location, const char *object,
                 int binary, const char *note);
/* The end line "// *** //". */
void foam_footer(Buf *b);

/* Shortest round-trip decimal (precision <= 0) or %.{precision}g.
   Writes at most 32 chars to s; returns the length. */
int foam_fmt_double(char *s, double x, int precision);
void foam_put_double(Buf *b, double x, int precision);

/* A list of n items of `width` doubles: ascii "n\n(\nx\n...)\n" with tuples
   as "(x y z)", or binary.  Used for points, internalField, values. */
void foam_put_scalars(Buf *b, const double *v, size_t n, int width, int binary, int precision);
/* A list of n int labels (ascii or binary). */
void foam_put_labels(Buf *b, const int *v, size_t n, int binary);
/* A list of integer lists: ascii "n(4(a b c d) ...)" (faceList) or binary
   faceCompactList (offsets list, then the flat list). */
void foam_put_faces(Buf *b, const int *off, const int *idx, size_t n, int binary);

/* Parses a decimal number at s (no leading space); returns the number of
   characters consumed (0 if none) and sets *x and *is_int.  Accepts the
   decimal forms strtod accepts ([+-]digits[.digits][e[+-]digits], ".5",
   "5."); nan/inf and hex floats are NOT numbers (they are words).  *x is
   bit-for-bit what strtod gives (inf on overflow): a fast path, exact for
   mantissas <= 2^53 and |exponent| <= 22, and strtod otherwise.  is_int:
   written without '.' or exponent.  s need not be NUL-terminated. */
size_t foam_parse_number(const char *s, const char *end, double *x, int *is_int);

#endif
