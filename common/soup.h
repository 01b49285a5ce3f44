/*
** soup.h: what the surface readers share: the triangle soup a reader
** collects (three corners per triangle, a region tag per triangle, the
** regions' names) before it is welded into a TriSurf, and the strict
** number syntax of their coordinates.
**
** The STL and OBJ readers both fill a Soup and hand it to soup_finish,
** so both formats go through the same welding (trisurf_from_soup:
** bit-identical corners become one point) and give the same TriSurf for
** the same triangles.  Regions are STL `solid` blocks and OBJ `g`/`o`
** groups; regions with the same name share one tag.
**
** Numbers are decimal only ([+-]digits[.digits][(e|E)[+-]digits], ".5",
** "5."), as foam_parse_number reads them: hex floats, "1.0.0", "1,5" or
** "0x" are malformed, which plain strtod would partly accept.  The words
** nan and inf/infinity (any case, signed), and old MSVC's spellings of
** them (1.#INF, -1.#IND00, 1.#QNAN0e+000), are numbers but not finite:
** exporters write "nan" in STL facet normals, which are skipped, while a
** coordinate must be finite.
*/
#ifndef KIESEL_SOUP_H
#define KIESEL_SOUP_H

#include <stddef.h>

#include "err.h"
#include "trisurf.h"

typedef struct Soup {
    double *xyz;       /* 9 per triangle */
    int *tag;          /* 1 per triangle */
    size_t n, cap;     /* triangles */
    char **names;      /* tag -> region name */
    int nnames;
    size_t names_cap;
} Soup;

/* A Soup is ready to use when zeroed ({0}). */
void soup_free(Soup *S);
/* Appends the triangle c[0..8] (three corners) with a region tag. */
void soup_push(Soup *S, const double c[9], int tag);
/* The tag of the region called name, a new one if there is none yet. */
int soup_tag(Soup *S, const char *name);
/* Moves the soup into s, welded; tagged != 0 keeps the tags and names.
   An empty soup or one too large for a TriSurf fails with "name: none"
   or a size message.  The soup is freed either way; s is empty on
   failure. */
int soup_finish(Soup *S, TriSurf *s, int tagged, const char *name, const char *none, Err *e);

/* The token t[0..n) as a number: 1 finite, 0 not finite (nan, inf, or a
   decimal that overflows; *x is then nan or +-inf), -1 not a number. */
int soup_number(const char *t, size_t n, double *x);

#endif
