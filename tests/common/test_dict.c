/*
** test_dict.c: the dictionary reader, look-ups, writer.
**
** Every syntax form of the OpenFOAM tutorials, every parser error with its
** exact line, regex and $variable semantics, binary lists built in memory,
** gzip, the write -> parse round trip, keyword suggestions, and a
** robustness sweep (every prefix of a file, random byte mutations).  The
** parse speed of a 10-million-scalar list is printed, not asserted.
*/
#include "dict.h"
#include "buf.h"
#include "foam.h"
#include "io.h"
#include "mem.h"

#include "test.h"

#include <stdint.h>
#include <time.h>

static Dict *parse(const char *text, Err *e) { return dict_parse(text, strlen(text), "test.dict", e); }

/* Parses text that must fail; returns the message (static storage). */
static const char *parse_error(const char *text)
{
    static Err e;
    e.msg[0] = '\0';
    Dict *d = parse(text, &e);
    if (d) {
        dict_free(d);
        return "(parsed without error)";
    }
    return e.msg;
}

static const DictNode *value_of(const Dict *d, const char *key)
{
    const DictEntry *en = dict_find_scoped(d, key);
    return en && en->nvals ? en->vals[en->nvals - 1] : NULL;
}

static const char *write_text(const Dict *d)
{
    static Buf b;
    buf_free(&b);
    dict_write(d, &b);
    return b.p ? b.p : "";
}

static char *scratch(const char *name)
{
    static char path[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", test_tmpdir(), name);
    return path[k];
}

static void put_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

/* ---- syntax ---- */

static const char controlDict[] =
    "/*--------------------------------*- C++ -*----------------------------------*\\\n"
    "| =========                 |                                                 |\n"
    "\\*---------------------------------------------------------------------------*/\n"
    "FoamFile\n"
    "{\n"
    "    version     2.0;\n"
    "    format      ascii;\n"
    "    class       dictionary;\n"
    "    location    \"system\";\n"
    "    object      controlDict;\n"
    "}\n"
    "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n"
    "\n"
    "application     icoFoam;\n"
    "startFrom       startTime;      // firstTime | startTime | latestTime\n"
    "startTime       0;\n"
    "endTime         0.5;\n"
    "deltaT          0.005;\n"
    "writeInterval   20;  /* a comment\n spanning lines */\n"
    "runTimeModifiable true;\n"
    "adjustTimeStep  yes;\n"
    "title           \"say \\\"hi\\\" \\\\ there\";\n"
    "g               (0 -9.81 0);\n"
    "functions\n"
    "{\n"
    "    probes { type probes; fields (p U); }\n"
    "}\n";

TEST(controldict_values)
{
    Err e;
    Dict *d = parse(controlDict, &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    const char *w = NULL;
    double x = 0, g[3] = {0};
    int i = 0, s = -1;
    EXPECT(dict_word(d, "application", &w, &e) == 0 && strcmp(w, "icoFoam") == 0, "application");
    EXPECT(dict_scalar(d, "endTime", &x, &e) == 0 && x == 0.5, "endTime %g", x);
    EXPECT(dict_scalar(d, "deltaT", &x, &e) == 0 && x == 0.005, "deltaT %.17g", x);
    EXPECT(dict_label(d, "writeInterval", &i, &e) == 0 && i == 20, "writeInterval %d", i);
    EXPECT(dict_switch(d, "runTimeModifiable", &s, &e) == 0 && s == 1, "runTimeModifiable");
    EXPECT(dict_switch(d, "adjustTimeStep", &s, &e) == 0 && s == 1, "adjustTimeStep");
    EXPECT(dict_switch_or(d, "missing", 0, &s, &e) == 0 && s == 0, "switch default");
    EXPECT(dict_word(d, "title", &w, &e) == 0 && strcmp(w, "say \"hi\" \\\\ there") == 0, "string '%s'", w);
    EXPECT(dict_vector(d, "g", g, &e) == 0 && g[0] == 0 && g[1] == -9.81 && g[2] == 0, "g");
    EXPECT(dict_header_class(d) && strcmp(dict_header_class(d), "dictionary") == 0, "class");
    EXPECT(dict_header_binary(d) == 0, "ascii");
    const DictEntry *en = dict_find_scoped(d, "functions.probes.type");
    EXPECT(en && en->line == 27 && strcmp(en->vals[0]->text, "probes") == 0, "scoped entry, line %d",
           en ? en->line : -1);
    en = dict_find(d, "runTimeModifiable");
    EXPECT(en && en->line == 21, "line after a multi-line comment: %d", en ? en->line : -1);
    const Dict *fn = dict_subdict(d, "functions", &e);
    EXPECT(fn && strcmp(fn->name, "functions") == 0, "sub-dictionary name");
    const Dict *pr = fn ? dict_subdict(fn, "probes", &e) : NULL;
    EXPECT(pr && strcmp(pr->name, "functions.probes") == 0, "scoped name '%s'", pr ? pr->name : "");
    double def = 7;
    EXPECT(dict_scalar_or(d, "nope", 3, &def, &e) == 0 && def == 3, "scalar default");
    dict_free(d);
}

TEST(typed_lookup_errors)
{
    Err e;
    Dict *d = parse("a abc;\nb 1.5;\nc { x 1; }\nd 1 2;\ne (1 2);\nf maybe;\n", &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    double x;
    int i;
    const char *w;
    double v[3];
    EXPECT(dict_scalar(d, "a", &x, &e) < 0, "a is no number");
    EXPECT(strcmp(e.msg, "test.dict:1: keyword 'a' in dictionary 'test.dict': expected a number, found word 'abc'") == 0,
           "%s", e.msg);
    EXPECT(dict_label(d, "b", &i, &e) < 0, "1.5 is no label");
    EXPECT(strcmp(e.msg, "test.dict:2: keyword 'b' in dictionary 'test.dict': expected an integer, found number '1.5'") == 0,
           "%s", e.msg);
    EXPECT(dict_scalar(d, "c", &x, &e) < 0, "c is a dictionary");
    CONTAINS(e.msg, "test.dict:3: keyword 'c'");
    CONTAINS(e.msg, "found a sub-dictionary");
    EXPECT(dict_scalar(d, "d", &x, &e) < 0, "two values");
    CONTAINS(e.msg, "test.dict:4: keyword 'd' in dictionary 'test.dict': expected a number, found 2 values");
    EXPECT(dict_vector(d, "e", v, &e) < 0, "2-vector");
    CONTAINS(e.msg, "test.dict:5: keyword 'e' in dictionary 'test.dict': expected a vector (x y z), found list of 2 items");
    EXPECT(dict_switch(d, "f", &i, &e) < 0, "maybe");
    CONTAINS(e.msg, "test.dict:6:");
    EXPECT(dict_word(d, "zzz", &w, &e) < 0, "missing");
    CONTAINS(e.msg, "keyword 'zzz' is missing in dictionary 'test.dict'");
    const Dict *c = dict_subdict(d, "c", &e);
    EXPECT(c && dict_word(c, "y", &w, &e) < 0, "missing in sub");
    CONTAINS(e.msg, "test.dict:3: keyword 'y' is missing in dictionary 'c'");
    EXPECT(dict_subdict(d, "a", &e) == NULL, "a is no dictionary");
    CONTAINS(e.msg, "test.dict:1: keyword 'a' in dictionary 'test.dict' is not a sub-dictionary");
    static const char *const fmts[] = {"ascii", "binary", NULL};
    Dict *d2 = parse("writeFormat binary;\nother asci;\n", &e);
    EXPECT(d2 && dict_choice_or(d2, "writeFormat", fmts, 0, &i, &e) == 0 && i == 1, "choice");
    EXPECT(d2 && dict_choice_or(d2, "missing", fmts, 0, &i, &e) == 0 && i == 0, "choice default");
    EXPECT(d2 && dict_choice_or(d2, "other", fmts, 0, &i, &e) < 0, "bad choice");
    CONTAINS(e.msg, "test.dict:2: keyword 'other' in dictionary 'test.dict': 'asci' is not one of: ascii, binary; did you mean 'ascii'?");
    dict_free(d2);
    dict_free(d);
}

TEST(lists_and_compaction)
{
    Err e;
    Dict *d = parse("vertices ( (0 0 0) (1 0 0) (1 1 0.5) );\n"
                    "faces 2(4(1 22 463 442) 3(4 5 6));\n"
                    "quads ( (3 7 6 2) (0 4 7 3) );\n"
                    "owner 5(0 0 1 1 2);\n"
                    "mixed (1 2.5 -3e2);\n"
                    "inGroups 1(wall);\n"
                    "fields (p U mag(U));\n"
                    "div(phi,U) Gauss linear;\n"
                    "arc arc 1 5 (1.1 0 0.5);\n"
                    "big 3\n(\n1\n2\n3\n);\n"
                    "empty 0();\n"
                    "noSize ();\n"
                    "huge (1 99999999999);\n",
                    &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    const DictNode *nd = value_of(d, "vertices");
    EXPECT(nd && nd->kind == DN_NUMS && nd->width == 3 && nd->n == 3 && nd->v[8] == 0.5, "vertices compact");
    nd = value_of(d, "faces");
    EXPECT(nd && nd->kind == DN_RAGGED && nd->n == 2 && nd->off[2] == 7 && nd->iv[3] == 442 && nd->iv[6] == 6,
           "ragged faces");
    int *off = NULL, *idx = NULL, *lab = NULL;
    size_t n = 0;
    EXPECT(nd && dict_node_faces(nd, &off, &idx, &n, &e) == 0 && n == 2 && off[1] == 4 && idx[4] == 4, "faces");
    free(off);
    free(idx);
    nd = value_of(d, "quads");
    EXPECT(nd && nd->kind == DN_NUMS && nd->width == 4, "equal tuples are NUMS");
    EXPECT(nd && dict_node_faces(nd, &off, &idx, &n, &e) == 0 && n == 2 && off[2] == 8 && idx[7] == 3,
           "faces from tuples");
    free(off);
    free(idx);
    nd = value_of(d, "owner");
    EXPECT(nd && nd->kind == DN_LABELS && nd->n == 5 && nd->iv[4] == 2, "labels");
    EXPECT(nd && dict_node_labels(nd, &lab, &n, &e) == 0 && n == 5 && lab[2] == 1, "labels copy");
    free(lab);
    nd = value_of(d, "mixed");
    EXPECT(nd && nd->kind == DN_NUMS && nd->width == 1 && nd->v[2] == -300, "scalars");
    EXPECT(nd && dict_node_labels(nd, &lab, &n, &e) < 0, "2.5 is no label");
    CONTAINS(e.msg, "test.dict:5: expected a list of integers");
    nd = value_of(d, "inGroups");
    EXPECT(nd && nd->kind == DN_LIST && nd->n == 1 && strcmp(nd->items[0]->text, "wall") == 0, "word list");
    nd = value_of(d, "fields");
    EXPECT(nd && nd->n == 3 && strcmp(nd->items[2]->text, "mag(U)") == 0, "word with parentheses");
    EXPECT(dict_find(d, "div(phi,U)") != NULL, "keyword with parentheses");
    const DictEntry *en = dict_find(d, "arc");
    EXPECT(en && en->nvals == 4 && en->vals[2]->kind == DN_NUMBER && en->vals[2]->num == 5 &&
               en->vals[3]->kind == DN_NUMS,
           "'5 (1.1 0 0.5)' on one line is a number then a list (%zu values)", en ? en->nvals : 0);
    nd = value_of(d, "big");
    EXPECT(nd && nd->kind == DN_LABELS && nd->n == 3, "N on its own line then the list");
    nd = value_of(d, "empty");
    EXPECT(nd && dict_node_len(nd) == 0, "0()");
    double *v = NULL;
    EXPECT(nd && dict_node_scalars(nd, 3, &v, &n, &e) == 0 && n == 0, "empty list converts");
    free(v);
    nd = value_of(d, "noSize");
    EXPECT(nd && nd->kind == DN_LIST && nd->n == 0, "()");
    nd = value_of(d, "huge");
    EXPECT(nd && nd->kind == DN_NUMS && nd->v[1] == 99999999999.0, "out-of-int integers are NUMS");
    v = NULL;
    nd = value_of(d, "vertices");
    EXPECT(nd && dict_node_scalars(nd, 3, &v, &n, &e) == 0 && n == 3 && v[3] == 1 && v[8] == 0.5, "scalars width 3");
    free(v);
    EXPECT(nd && dict_node_scalars(nd, 2, &v, &n, &e) < 0, "width mismatch");
    CONTAINS(e.msg, "test.dict:1: expected a list of 2-tuples, found list of 3 3-tuples");
    dict_free(d);
}

TEST(general_path_equals_fast_path)
{
    /* A comment inside a list forces the general path; results match. */
    Err e;
    Dict *a = parse("x ( (0 0 0) (1 2 3) ); y (1 2 3); z 2(3(1 2 3) 2(4 5)); w 2(2(1 2) 2(3 4));", &e);
    Dict *b = parse("x ( (0 0 0) /*c*/ (1 2 3) ); y (1 /*c*/ 2 3); z 2(3(1 2 3) /*c*/ 2(4 5)); w 2(2(1 2) //\n 2(3 4));",
                    &e);
    EXPECT(a && b, "%s", e.msg);
    if (!a || !b) return;
    static const char *keys[] = {"x", "y", "z", "w"};
    for (int k = 0; k < 4; k++) {
        const DictNode *p = value_of(a, keys[k]), *q = value_of(b, keys[k]);
        EXPECT(p && q && p->kind == q->kind && p->n == q->n && p->width == q->width, "%s: kinds %d %d", keys[k],
               p ? (int)p->kind : -1, q ? (int)q->kind : -1);
    }
    char *wa = strdup(write_text(a));
    EXPECT(strcmp(wa, write_text(b)) == 0, "same text written:\n%s\n---\n%s", wa, write_text(b));
    free(wa);
    dict_free(a);
    dict_free(b);
}

TEST(size_then_list_on_one_line)
{
    Err e;
    /* a size that does not count its list is refused by the parser, not
       only where the value is used (issue 9) */
    const char *msg = parse_error("x 3 (0 0.5 1);\nbad 4 (1 2 3);\narc 1 5 (1.1 0 0.5);\n");
    CONTAINS(msg, "test.dict:2: keyword 'bad': list size 4 does not match the 3 items read");
    Dict *d = parse("x 3 (0 0.5 1);\narc 1 5 (1.1 0 0.5);\n", &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    const DictNode *nd = dict_entry_value(dict_find(d, "x"), &e);
    EXPECT(nd && dict_node_len(nd) == 3, "size and list on one line not taken as one list: %s", e.msg);
    /* several values where one is expected: still an error */
    nd = dict_entry_value(dict_find(d, "arc"), &e);
    EXPECT(!nd, "arc accepted as a single value");
    CONTAINS(e.msg, "expected a single value, found 3 values");
    dict_free(d);
}

TEST(dimensions_and_uniform)
{
    Err e;
    Dict *d = parse("dimensions [0 1 -1 0 0 0 0];\nnu [m^2 s^-1] 1e-05;\n"
                    "internalField uniform (0 0 0);\n"
                    "p nonuniform List<scalar> 3(1 2 3);\n"
                    "q nonuniform 0();\n"
                    "r List<scalar> 4{0.5};\n"
                    "s List<vector> 2{(1 2 3)};\n"
                    "t 3{0};\n",
                    &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    const DictEntry *en = dict_find(d, "dimensions");
    EXPECT(en && en->vals[0]->kind == DN_DIMS && en->vals[0]->n == 7 && en->vals[0]->items[2]->num == -1, "dims");
    en = dict_find(d, "nu");
    EXPECT(en && en->nvals == 2 && en->vals[0]->n == 2 && strcmp(en->vals[0]->items[1]->text, "s^-1") == 0 &&
               en->vals[1]->num == 1e-5,
           "unit dims");
    en = dict_find(d, "p");
    EXPECT(en && en->nvals == 3 && en->vals[2]->kind == DN_LABELS && en->vals[2]->n == 3, "nonuniform");
    en = dict_find(d, "q");
    EXPECT(en && en->nvals == 2 && dict_node_len(en->vals[1]) == 0, "nonuniform 0()");
    const DictNode *nd = value_of(d, "r");
    EXPECT(nd && nd->kind == DN_NUMS && nd->n == 4 && nd->v[3] == 0.5, "4{0.5}");
    nd = value_of(d, "s");
    EXPECT(nd && nd->kind == DN_NUMS && nd->n == 2 && nd->width == 3 && nd->v[5] == 3, "2{(1 2 3)}");
    nd = value_of(d, "t");
    EXPECT(nd && nd->kind == DN_LABELS && nd->n == 3 && nd->iv[2] == 0, "3{0}");
    dict_free(d);
}

TEST(boundary_list_of_dicts)
{
    Err e;
    Dict *d = parse("FoamFile { version 2.0; format ascii; class polyBoundaryMesh; object boundary; }\n"
                    "3\n(\n    movingWall\n    {\n        type wall;\n        inGroups 1(wall);\n"
                    "        nFaces 20;\n        startFace 760;\n    }\n"
                    "    fixedWalls { type wall; nFaces 60; startFace 780; }\n"
                    "    frontAndBack { type empty; nFaces 800; startFace 840; }\n)\n"
                    "// ************************************************************************* //\n",
                    &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    const DictEntry *en = dict_find(d, "");
    EXPECT(en && en->nvals == 1 && en->vals[0]->kind == DN_LIST && en->vals[0]->n == 6, "bare list of 3 pairs");
    if (en && en->nvals == 1 && en->vals[0]->n == 6) {
        const DictNode *l = en->vals[0];
        EXPECT(l->items[0]->kind == DN_WORD && l->items[1]->kind == DN_DICT, "word, dict");
        int nf = 0;
        EXPECT(dict_label(l->items[5]->dict, "nFaces", &nf, &e) == 0 && nf == 800, "nFaces %d", nf);
        EXPECT(strcmp(l->items[1]->dict->name, "movingWall") == 0, "dict named by its word '%s'",
               l->items[1]->dict->name);
    }
    EXPECT(strstr(parse_error("2\n(\na { x 1; }\nb { x 1; }\nc { x 1; }\n)\n"), "test.dict:1: list size 2 does not match the 6 items read"),
           "pairs counted: %s", parse_error("2\n(\na { x 1; }\nb { x 1; }\nc { x 1; }\n)\n"));
    dict_free(d);
}

/* ---- regex keys and variables ---- */

TEST(regex_keys)
{
    Err e;
    Dict *d = parse("\".*\" 1;\n\"(U|k)Final\" 2;\nUFinal 3;\n\"(U|k|epsilon)Final\" 4;\n\"(?i)wall.*\" 5;\n"
                    "\"alpha.water.*\" { n 6; }\n",
                    &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    int i = 0;
    EXPECT(dict_label(d, "UFinal", &i, &e) == 0 && i == 3, "literal first: %d", i);
    EXPECT(dict_label(d, "kFinal", &i, &e) == 0 && i == 4, "last matching regex wins: %d", i);
    EXPECT(dict_label(d, "p", &i, &e) == 0 && i == 1, "catch-all: %d", i);
    EXPECT(dict_label(d, "WALLs", &i, &e) == 0 && i == 5, "(?i): %d", i);
    EXPECT(dict_label(d, "xkFinal", &i, &e) == 0 && i == 1, "whole-key match only: %d", i);
    const Dict *a = dict_subdict(d, "alpha.water.1", &e);
    EXPECT(a && dict_label(a, "n", &i, &e) == 0 && i == 6, "regex sub-dictionary");
    EXPECT(strstr(parse_error("a 1;\n\"(bad\" 2;\n"), "test.dict:2: invalid regular expression \"(bad\""), "%s",
           parse_error("a 1;\n\"(bad\" 2;\n"));
    EXPECT(strstr(parse_error("\"a{1000}{1000}\" 2;\n"), "test.dict:1: invalid regular expression"), "%s",
           parse_error("\"a{1000}{1000}\" 2;\n"));
    EXPECT(strstr(parse_error("\"h+++++++++++++++++++++++++++++++++++++a\" 2;\n"), "repetitions too deeply nested"),
           "%s", parse_error("\"h+++++++++++++++++++++++++++++++++++++a\" 2;\n"));
    EXPECT(strstr(parse_error("\"((((((((((((((((((((a+)+)+)+)+)+)+)+)+)+)+)+)+)+)+)+)+)+)+)+)+\" 2;\n"),
                  "repetitions too deeply nested"),
           "nested repetitions");
    dict_free(d);
}

TEST(variables)
{
    Err e;
    Dict *d = parse("x 0.5;\n"
                    "v (1 2 3);\n"
                    "top { a 1; b { c 7; } }\n"
                    "solvers\n{\n"
                    "    p { solver PCG; tolerance 1e-6; relTol 0.05; }\n"
                    "    pFinal { $p; relTol 0; }\n"
                    "    \"(U|k)\" { solver smooth; }\n"
                    "    UFinal { $U; tolerance $x; }\n"
                    "    deep { inner { y $...p.solver; z $:top.b.c; w $top.a; } yy 3; }\n"
                    "}\n"
                    "copy $top;\n"
                    "useV uniform $v;\n"
                    "scoped $top.b.c;\n"
                    "braced ${x};\n",
                    &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    const Dict *pf = dict_subdict(dict_subdict_opt(d, "solvers"), "pFinal", &e);
    const char *w = NULL;
    double x = -1;
    int i = 0;
    EXPECT(pf && dict_word(pf, "solver", &w, &e) == 0 && strcmp(w, "PCG") == 0, "merged solver");
    EXPECT(pf && dict_scalar(pf, "relTol", &x, &e) == 0 && x == 0, "override after merge: %g", x);
    EXPECT(pf && dict_scalar(pf, "tolerance", &x, &e) == 0 && x == 1e-6, "merged tolerance");
    const Dict *uf = dict_subdict(dict_subdict_opt(d, "solvers"), "UFinal", &e);
    EXPECT(uf && dict_word(uf, "solver", &w, &e) == 0 && strcmp(w, "smooth") == 0, "$U through a regex key");
    EXPECT(uf && dict_scalar(uf, "tolerance", &x, &e) == 0 && x == 0.5, "$x from the top");
    const DictEntry *en = dict_find_scoped(d, "solvers.deep.inner.y");
    EXPECT(en && en->nvals == 1 && strcmp(en->vals[0]->text, "PCG") == 0, "$...p.solver");
    EXPECT(strstr(parse_error("s { p 1; d { i { y $..p; } } }"), "undefined variable $..p"), "$..p is the parent only");
    EXPECT(dict_find_scoped(d, "solvers.deep.inner.z") && value_of(d, "solvers.deep.inner.z")->num == 7, "$:top.b.c");
    EXPECT(dict_find_scoped(d, "solvers.deep.inner.w") && value_of(d, "solvers.deep.inner.w")->num == 1, "$top.a upward");
    EXPECT(strstr(parse_error("a { b 1; c { d $.b; } }"), "test.dict:1: undefined variable $.b"),
           "$.b is this level only: %s", parse_error("a { b 1; c { d $.b; } }"));
    const Dict *c = dict_subdict(d, "copy", &e);
    EXPECT(c && dict_label(c, "a", &i, &e) == 0 && i == 1, "key $dict; is a sub-dictionary copy");
    EXPECT(c && dict_subdict_opt(c, "b") && strcmp(dict_subdict_opt(c, "b")->name, "copy.b") == 0,
           "copied names '%s'", c && dict_subdict_opt(c, "b") ? dict_subdict_opt(c, "b")->name : "");
    en = dict_find(d, "useV");
    EXPECT(en && en->nvals == 2 && en->vals[1]->kind == DN_LABELS && en->vals[1]->n == 3, "uniform $v");
    EXPECT(dict_label(d, "scoped", &i, &e) == 0 && i == 7, "$top.b.c");
    EXPECT(dict_scalar(d, "braced", &x, &e) == 0 && x == 0.5, "${x}");
    EXPECT(strcmp(parse_error("a 1;\nb\n{\n    c $foo;\n}\n"), "test.dict:4: undefined variable $foo") == 0, "%s",
           parse_error("a 1;\nb\n{\n    c $foo;\n}\n"));
    EXPECT(strcmp(parse_error("a 1;\nb { $a; }\n"),
                  "test.dict:2: variable $a is not a dictionary and cannot be merged here") == 0,
           "%s", parse_error("a 1;\nb { $a; }\n"));
    EXPECT(strcmp(parse_error("b $later;\nlater 1;\n"), "test.dict:1: undefined variable $later") == 0,
           "only entries above are visible");
    EXPECT(strcmp(parse_error("d { a 1; }\nx\n{\n    k $d bounds (0 0 1);\n}\n"),
                  "test.dict:4: keyword 'k': a dictionary variable cannot be followed by other values") == 0,
           "%s", parse_error("d { a 1; }\nx\n{\n    k $d bounds (0 0 1);\n}\n"));
    dict_free(d);
}

TEST(merge_and_replace)
{
    Err e;
    Dict *d = parse("a 1;\nb { x 1; y 2; }\na 2;\nb { y 3; z 4; }\nc 5;\n#remove c\n#remove (\"z.*\")\n", &e);
    EXPECT(d, "%s", e.msg);
    if (!d) return;
    int i = 0;
    EXPECT(d->n == 2 && strcmp(d->entries[0].key, "a") == 0, "a replaced in place (%zu entries)", d->n);
    EXPECT(dict_label(d, "a", &i, &e) == 0 && i == 2, "a = %d", i);
    const Dict *b = dict_subdict_opt(d, "b");
    EXPECT(b && b->n == 3 && dict_label(b, "y", &i, &e) == 0 && i == 3, "b merged");
    EXPECT(!dict_find(d, "c"), "#remove c");
    dict_free(d);
    d = parse("zeta 1; zappa 2; keep 3;\n#remove \"z.*\"\n", &e);
    EXPECT(d && d->n == 1 && dict_find(d, "keep"), "#remove regex");
    dict_free(d);
}

/* ---- directives and includes ---- */

TEST(includes)
{
    char *dir = scratch("inc");
    Err e;
    io_mkdir_p(dir, &e);
    char main_path[600], sub[600], cyc[600], deep[600];
    snprintf(main_path, sizeof main_path, "%s/main", dir);
    snprintf(sub, sizeof sub, "%s/common", dir);
    put_file(sub, "FoamFile { version 2.0; format ascii; class dictionary; object common; }\n"
                  "nu 1e-3;\nrho 1000;\n");
    put_file(main_path, "FoamFile { version 2.0; format ascii; class dictionary; object main; }\n"
                        "#include \"common\"\n"
                        "#includeEtc \"caseDicts/setConstraintTypes\"\n"
                        "#includeFunc residuals\n"
                        "mu $nu;\n");
    Dict *d = dict_read(main_path, &e);
    EXPECT(d, "%s", e.msg);
    if (d) {
        double x = 0;
        EXPECT(dict_scalar(d, "mu", &x, &e) == 0 && x == 1e-3, "included variable");
        EXPECT(dict_find(d, "FoamFile") && d->entries[0].file == d->file, "main header kept, included one dropped");
        int nff = 0;
        for (size_t i = 0; i < d->n; i++) nff += strcmp(d->entries[i].key, "FoamFile") == 0;
        EXPECT(nff == 1 && d->n == 4, "entries %zu", d->n);
        const DictEntry *en = dict_find(d, "rho");
        EXPECT(en && en->line == 3 && strcmp(en->file, sub) == 0, "included entry knows its file:line");
        EXPECT(dict_nwarnings(d) == 2, "warnings %zu", dict_nwarnings(d));
        EXPECT(dict_nwarnings(d) == 2 && strstr(dict_warning(d, 0), ":3: #includeEtc caseDicts/setConstraintTypes ignored"),
               "%s", dict_nwarnings(d) ? dict_warning(d, 0) : "");
        dict_free(d);
    }
    put_file(main_path, "a { #include \"common\" }\n");
    d = dict_read(main_path, &e);
    EXPECT(d && dict_subdict_opt(d, "a") && dict_subdict_opt(d, "a")->n == 2 && !dict_find(dict_subdict_opt(d, "a"), "FoamFile"),
           "include inside a sub-dictionary drops the header: %s", d ? "" : e.msg);
    dict_free(d);
    snprintf(cyc, sizeof cyc, "%s/cyc", dir);
    put_file(cyc, "a 1;\n#include \"cyc\"\n");
    d = dict_read(cyc, &e);
    EXPECT(!d, "cycle detected");
    CONTAINS(e.msg, "cyc:2: #include cycle");
    put_file(cyc, "a 1;\n\n#include \"nothere\"\n");
    d = dict_read(cyc, &e);
    EXPECT(!d, "missing include");
    CONTAINS(e.msg, "cyc:3: cannot open included file");
    put_file(cyc, "a 1;\n#includeIfPresent \"nothere\"\nb 2;\n");
    d = dict_read(cyc, &e);
    EXPECT(d && dict_find(d, "b"), "#includeIfPresent of a missing file");
    dict_free(d);
    /* a chain deeper than the limit: d0 includes d1 includes ... d20 */
    for (int k = 0; k <= 20; k++) {
        snprintf(deep, sizeof deep, "%s/d%d", dir, k);
        char text[64];
        snprintf(text, sizeof text, "x%d 1;\n#include \"d%d\"\n", k, k + 1);
        put_file(deep, k == 20 ? "end 1;\n" : text);
    }
    snprintf(deep, sizeof deep, "%s/d0", dir);
    d = dict_read(deep, &e);
    EXPECT(!d, "include depth limit");
    CONTAINS(e.msg, "#include nested too deeply (limit 16)");
    snprintf(deep, sizeof deep, "%s/d10", dir);
    d = dict_read(deep, &e);
    EXPECT(d && dict_find(d, "end") && dict_find(d, "x19"), "10 levels are fine: %s", d ? "" : e.msg);
    dict_free(d);
    /* an error inside an included file names that file and the includer */
    put_file(sub, "a 1;\nb 2\n");
    put_file(main_path, "x 1;\n#include \"common\"\n");
    d = dict_read(main_path, &e);
    EXPECT(!d, "error in include");
    char want[1400];
    snprintf(want, sizeof want, "%s:2: expected ';' after value of keyword 'b' (included from %s:2)", sub, main_path);
    EXPECT(strcmp(e.msg, want) == 0, "'%s'", e.msg);
}

TEST(unsupported_directives)
{
    EXPECT(strcmp(parse_error("a 1;\n#calc \"1+2\";\n"), "test.dict:2: directive #calc is not supported") == 0, "%s",
           parse_error("a 1;\n#calc \"1+2\";\n"));
    EXPECT(strcmp(parse_error("\n\n#codeStream { code #{ #}; }\n"), "test.dict:3: directive #codeStream is not supported") == 0,
           "%s", parse_error("\n\n#codeStream { code #{ #}; }\n"));
    EXPECT(strcmp(parse_error("#if 1\n"), "test.dict:1: directive #if is not supported") == 0, "#if");
    EXPECT(strcmp(parse_error("#ifeq a b\n"), "test.dict:1: directive #ifeq is not supported") == 0, "#ifeq");
    EXPECT(strcmp(parse_error("a\n#eval{1+2};\n"), "test.dict:2: directive #eval is not supported") == 0, "%s",
           parse_error("a\n#eval{1+2};\n"));
    EXPECT(strcmp(parse_error("code #{ int x; #};\n"), "test.dict:1: verbatim code blocks #{ ... #} are not supported") == 0,
           "%s", parse_error("code #{ int x; #};\n"));
}

/* ---- errors with their lines ---- */

TEST(parse_errors_exact)
{
    static const struct { const char *text, *msg; } cases[] = {
        {"a 1;\nb 2\n}\n", "test.dict:2: expected ';' after value of keyword 'b'"},
        {"a 1;\nb 2", "test.dict:2: expected ';' after value of keyword 'b'"},
        {"a 1;\n\nb (1 2\n3 4;\n", "test.dict:4: unexpected ';' inside the list started at line 3"},
        {"a 1;\n\nb (1 2\n3 4\n", "test.dict:3: unterminated list started at line 3"},
        {"a 1;\n}\n", "test.dict:2: unmatched '}'"},
        {"a 1;\nb (1 2));\n", "test.dict:2: unmatched ')'"},
        {"a 1;\nb \"abc;\n\n", "test.dict:2: unterminated string"},
        {"a 1;\n/* open\n\ncomment", "test.dict:2: unterminated comment"},
        {"a 1;\n\nb 5(1 2 3 4);\n", "test.dict:3: list size 5 does not match the 4 items read"},
        {"a (\n2(5 -1)\n3(5 -1));\n", "test.dict:3: list size 3 does not match the 2 items read"},
        {"a 1;\nb\n{\n  c 1;\n", "test.dict:3: unterminated dictionary started at line 3"},
        {"a 1;\n[ b;\n", "test.dict:2: expected a keyword, found '['"},
        {"dims [0 1 -1 0\n0 0 0", "test.dict:1: unterminated dimension set started at line 1"},
        {"dims [0 1 -1 0\n0 0 0;\n", "test.dict:2: unexpected ';' in the dimension set started at line 1"},
        {"x 1e999;\n", "test.dict:1: number '1e999' is out of range"},
        {"x 1;\ny $\n", "test.dict:2: expected a variable name after '$'"},
        {"x (1 2 3) 3{1 2};\n", "test.dict:1: expected one value and '}' in the uniform list 3{...}"},
        {"a\n\0;\n", "test.dict:2: unexpected NUL byte"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        Err e;
        e.msg[0] = '\0';
        size_t n = strlen(cases[i].text);
        if (i == sizeof cases / sizeof cases[0] - 1) n = 5;   /* the NUL case */
        Dict *d = dict_parse(cases[i].text, n, "test.dict", &e);
        EXPECT(!d && strcmp(e.msg, cases[i].msg) == 0, "case %zu: got '%s', expected '%s'", i, d ? "(parsed)" : e.msg,
               cases[i].msg);
        dict_free(d);
    }
}

/* ---- the FoamFile header (issue 9): OpenFOAM v1912's checks ---- */

TEST(header_checks)
{
    static const struct { const char *text, *msg; } bad[] = {
        {"FoamFile\n{\n    version 2.0 nan;\n    format ascii;\n    class dictionary;\n    object x;\n}\na 1;\n",
         "test.dict:3: FoamFile header: entry 'version' has 1 excess token (word 'nan'...), expected one number; "
         "a missing ';'?"},
        {"FoamFile\n{\n    version 2.0;\n    format ascii\n    class dictionary;\n    object x;\n}\n",
         "test.dict:4: FoamFile header: entry 'format' has 2 excess tokens (word 'class'...), expected one word; "
         "a missing ';'?"},
        {"FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n    object x\n}\n",
         "test.dict:6: expected ';' after value of keyword 'object'"},
        {"FoamFile { version abc; format ascii; object x; }\n",
         "test.dict:1: FoamFile header: 'version' must be one number, found word 'abc'"},
        {"FoamFile { format 1; object x; }\n", "test.dict:1: FoamFile header: 'format' must be one word, found number '1'"},
        {"FoamFile\n{\n format binar;\n object x;\n}\n",
         "test.dict:3: FoamFile header: format 'binar' is neither ascii nor binary"},
        {"FoamFile\n{\n format ascii;\n class dictionary;\n}\n", "test.dict:1: FoamFile header: entry 'object' is missing"},
        {"FoamFile { object x; }\n", "test.dict:1: FoamFile header: entry 'format' is missing"},
        {"FoamFile { format ascii; class (a b); object x; }\n",
         "test.dict:1: FoamFile header: 'class' must be one word, found list of 2 items"},
        {"FoamFile { format ascii; object { a 1; } }\n",
         "test.dict:1: FoamFile header: 'object' must be one word, found a sub-dictionary"},
        {"FoamFile { format ascii; object x; arch \"LSB;label=16;scalar=64\"; }\n",
         "test.dict:1: FoamFile header: arch \"LSB;label=16;scalar=64\": label= must be 32 or 64"},
        {"FoamFile { format binary; object x; arch \"MSB;label=32;scalar=64\"; }\n",
         "test.dict:1: FoamFile header: arch \"MSB;label=32;scalar=64\": big-endian binary files are not supported"},
        {"a 1;\nFoamFile { format ascii; object x; }\n",
         "test.dict:2: FoamFile header after other entries: it must come first, as OpenFOAM reads it"},
        {"FoamFile 3;\n", "test.dict:1: FoamFile header must be a dictionary"},
        {"a { FoamFile { format ascii; object x; } }\n$a;\n",
         "test.dict:2: $a would bring a FoamFile header into the top level"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *msg = parse_error(bad[i].text);
        EXPECT(strncmp(msg, bad[i].msg, strlen(bad[i].msg)) == 0, "case %zu: got '%s', expected '%s'", i, msg,
               bad[i].msg);
    }
    /* accepted: no version or class (read by the Foundation's OpenFOAM),
       quoted words, version 2, note and location as OpenFOAM leaves them,
       a FoamFile sub-dictionary below the top level */
    static const char *const good[] = {
        "FoamFile { format ascii; object x; }\na 1;\n",
        "FoamFile { version 2; format \"binary\"; class \"dictionary\"; object \"x\"; arch \"LSB;label=64;scalar=32\"; }\n",
        "FoamFile { version 2.0; format ascii; class volScalarField; note \"a\" b; location \"0\" c; object p; }\n",
        "a { FoamFile 3; }\n",
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        const char *msg = parse_error(good[i]);
        EXPECT(strcmp(msg, "(parsed without error)") == 0, "good case %zu refused: %s", i, msg);
    }
    /* an included file's header is checked too, and named with its line */
    char *inc = scratch("badheader.inc"), *top = scratch("top.dict");
    put_file(inc, "\nFoamFile { version 2.0 x; format ascii; object y; }\nb 2;\n");
    put_file(top, "FoamFile { version 2.0; format ascii; object x; }\n#include \"badheader.inc\"\n");
    Err e;
    Dict *d = dict_read(top, &e);
    EXPECT(!d, "bad header in an included file accepted");
    CONTAINS(e.msg, "badheader.inc:2: FoamFile header: entry 'version' has 1 excess token");
    CONTAINS(e.msg, "(included from ");
    dict_free(d);
}

/* ---- size prefixes are checked by the parser, wherever a list is read ---- */

TEST(list_sizes_everywhere)
{
    static const struct { const char *text, *msg; } bad[] = {
        {"a 1;\nlist 3 ( 1 2 );\n", "test.dict:2: keyword 'list': list size 3 does not match the 2 items read"},
        {"p nonuniform List<scalar> 3 (1 2);\n", "test.dict:1: p: list size 3 does not match the 2 items read"},
        {"w List<word> 1 (a b);\n", "test.dict:1: w: list size 1 does not match the 2 items read"},
        {"x ( List<label>\n2 (1 2 3) );\n", "test.dict:2: list size 2 does not match the 3 items read"},
        {"x (3(1 2) 2(1 2));\n", "test.dict:1: list size 3 does not match the 2 items read"},
        {"x 2((1 2) (3 4) (5 6));\n", "test.dict:1: list size 2 does not match the 3 items read"},
        {"x\n(\n    2\n    (a b c)\n);\n", "test.dict:3: list size 2 does not match the 3 items read"},
        {"3 (0 1)\n", "test.dict:1: list size 3 does not match the 2 items read"},
        {"b 4 ( a { } c { } );\n", "test.dict:1: keyword 'b': list size 4 does not match the 4 items read (2 "
                                   "name-dictionary pairs: the size counts the pairs)"},
        {"4\n(\na { }\nc { }\n)\n", "test.dict:1: list size 4 does not match the 4 items read (2 name-dictionary "
                                   "pairs: the size counts the pairs)"},
        {"n 3;\nx $n (1 2);\n", "test.dict:2: keyword 'x': list size 3 does not match the 2 items read"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *msg = parse_error(bad[i].text);
        EXPECT(strcmp(msg, bad[i].msg) == 0, "case %zu: got '%s', expected '%s'", i, msg, bad[i].msg);
    }
    Err e;
    Dict *d = parse("x 2 (1 2);\narc 1 5 (0 1 0);\nl List<scalar> 2 (1 2);\nb 2 ( a { } c { } );\nz 0 ();\n"
                    "e ( arc 0 1 (0.5 0 0) );\nt (3 (1 2));\n",
                    &e);
    EXPECT(d, "consistent sizes refused: %s", e.msg);
    if (d) {
        EXPECT(dict_set(d, "y", "3 (1 2)", &e) == -1, "dict_set accepted a wrong size");
        CONTAINS(e.msg, "keyword 'y': list size 3 does not match the 2 items read");
        EXPECT(dict_set(d, "y", "List<scalar> 2 (1 2)", &e) == 0, "dict_set: %s", e.msg);
        /* written and read back: same text */
        char *w1 = mem_strdup(write_text(d));
        Dict *d2 = parse(w1, &e);
        EXPECT(d2 && strcmp(write_text(d2), w1) == 0, "round trip: %s", d2 ? write_text(d2) : e.msg);
        dict_free(d2);
        free(w1);
    }
    dict_free(d);
}

/* ---- binary ---- */

static void put_doubles(Buf *b, const double *v, size_t n) { buf_put(b, v, n * sizeof(double)); }

TEST(binary_lists)
{
    const double pts[] = {0, 0, 0, 1.5, -2, 1e-300, 0.1, 0.2, 0.3};
    Buf b;
    buf_init(&b);
    foam_header(&b, "vectorField", "constant/polyMesh", "points", 1, NULL);
    foam_put_scalars(&b, pts, 3, 3, 1, 0);
    foam_footer(&b);
    Err e;
    Dict *d = dict_parse(b.p, b.n, "points", &e);
    EXPECT(d, "%s", e.msg);
    const DictNode *nd = d ? value_of(d, "") : NULL;
    EXPECT(nd && nd->kind == DN_NUMS && nd->width == 3 && nd->n == 3 && memcmp(nd->v, pts, sizeof pts) == 0,
           "binary points bit-exact");
    EXPECT(d && dict_header_binary(d) == 1, "binary header");
    dict_free(d);

    /* faceCompactList: offsets then indices, two bare lists */
    const int off[] = {0, 4, 7}, idx[] = {1, 22, 463, 442, 4, 5, 6};
    buf_clear(&b);
    foam_header(&b, "faceCompactList", NULL, "faces", 1, NULL);
    foam_put_faces(&b, off, idx, 2, 1);
    d = dict_parse(b.p, b.n, "faces", &e);
    EXPECT(d, "%s", e.msg);
    const DictEntry *en = d ? dict_find(d, "") : NULL;
    EXPECT(en && en->nvals == 2 && en->vals[0]->kind == DN_LABELS && en->vals[0]->n == 3 &&
               en->vals[1]->n == 7 && en->vals[1]->iv[2] == 463,
           "faceCompactList");
    dict_free(d);

    /* a field: List<scalar> and List<vector> in binary, 0-size without brackets */
    const double sv[] = {545.337, -1, 2.5e-8};
    buf_clear(&b);
    foam_header(&b, "volScalarField", "0.1", "T", 1, NULL);
    buf_puts(&b, "dimensions [0 0 0 1 0 0 0];\ninternalField nonuniform List<scalar> ");
    foam_put_scalars(&b, sv, 3, 1, 1, 0);
    buf_puts(&b, ";\nboundaryField\n{\n    wall { type fixedValue; value nonuniform List<scalar> ");
    foam_put_scalars(&b, sv, 0, 1, 1, 0);
    buf_puts(&b, ";\n    inGroups 1(wall); }\n    v { value nonuniform List<vector> ");
    foam_put_scalars(&b, pts, 3, 3, 1, 0);
    buf_puts(&b, ";\n    }\n}\n");
    d = dict_parse(b.p, b.n, "T", &e);
    EXPECT(d, "%s", e.msg);
    nd = d ? value_of(d, "internalField") : NULL;
    EXPECT(nd && nd->kind == DN_NUMS && nd->n == 3 && memcmp(nd->v, sv, sizeof sv) == 0, "binary scalars");
    nd = d ? value_of(d, "boundaryField.wall.value") : NULL;
    EXPECT(nd && dict_node_len(nd) == 0, "empty binary list without brackets");
    nd = d ? value_of(d, "boundaryField.wall.inGroups") : NULL;
    EXPECT(nd && nd->kind == DN_LIST && strcmp(nd->items[0]->text, "wall") == 0, "ascii word list in binary file");
    nd = d ? value_of(d, "boundaryField.v.value") : NULL;
    EXPECT(nd && nd->kind == DN_NUMS && nd->width == 3 && nd->v[5] == 1e-300, "binary vectors");
    dict_free(d);

    /* truncated data */
    buf_clear(&b);
    foam_header(&b, "volVectorField", NULL, "U", 1, NULL);
    buf_puts(&b, "internalField nonuniform List<vector>\n4\n(");
    put_doubles(&b, pts, 9);
    d = dict_parse(b.p, b.n, "U", &e);
    EXPECT(!d, "truncated binary list");
    EXPECT(strstr(e.msg, "U:19: binary list of 4 vectors truncated (needs 96 bytes, 72 left)"), "%s", e.msg);
    dict_free(d);

    /* arch label=64, scalar=32 */
    buf_clear(&b);
    buf_puts(&b, "FoamFile { version 2.0; format binary; arch \"LSB;label=64;scalar=32\"; class dictionary; object x; }\n"
                 "a List<label> 2(");
    const int64_t l64[] = {7, -3};
    buf_put(&b, l64, sizeof l64);
    buf_puts(&b, ");\nb List<scalar> 2(");
    const float f32[] = {0.5f, -1.25f};
    buf_put(&b, f32, sizeof f32);
    buf_puts(&b, ");\n");
    d = dict_parse(b.p, b.n, "x", &e);
    EXPECT(d, "%s", e.msg);
    nd = d ? value_of(d, "a") : NULL;
    EXPECT(nd && nd->kind == DN_LABELS && nd->iv[0] == 7 && nd->iv[1] == -3, "64-bit labels");
    nd = d ? value_of(d, "b") : NULL;
    EXPECT(nd && nd->kind == DN_NUMS && nd->v[0] == 0.5 && nd->v[1] == -1.25, "32-bit scalars");
    dict_free(d);
    buf_free(&b);
}

/* ---- gzip ---- */

TEST(gzip_read)
{
    char *path = scratch("gz_dict");
    Err e;
    const char text[] = "FoamFile { version 2.0; format ascii; class dictionary; object x; }\nvalue 42;\n";
    EXPECT(io_write_atomic(path, text, strlen(text), 1, &e) == 0, "%s", e.msg);
    Dict *d = dict_read(path, &e);   /* falls back to path.gz */
    int i = 0;
    EXPECT(d && dict_label(d, "value", &i, &e) == 0 && i == 42, "read through .gz: %s", d ? "" : e.msg);
    EXPECT(d && strstr(d->file, "gz_dict.gz"), "file name is the one read: %s", d ? d->file : "");
    dict_free(d);
    char gz[600];
    snprintf(gz, sizeof gz, "%s.gz", path);
    d = dict_read(gz, &e);
    EXPECT(d && dict_find(d, "value"), "read .gz by name");
    dict_free(d);
}

/* ---- round trip ---- */

/* Trees equal up to the compact kind of numeric lists (1.0 written as 1
   reads back as an integer). */
static int same_node(const DictNode *a, const DictNode *b);
static int same_dict(const Dict *a, const Dict *b)
{
    if (a->n != b->n) return 0;
    for (size_t i = 0; i < a->n; i++) {
        const DictEntry *x = &a->entries[i], *y = &b->entries[i];
        if (strcmp(x->key, y->key) || x->is_regex != y->is_regex || !x->dict != !y->dict || x->nvals != y->nvals)
            return 0;
        if (x->dict && !same_dict(x->dict, y->dict)) return 0;
        for (size_t k = 0; k < x->nvals; k++)
            if (!same_node(x->vals[k], y->vals[k])) return 0;
    }
    return 1;
}

static int same_node(const DictNode *a, const DictNode *b)
{
    Err e;
    if ((a->kind == DN_NUMS || a->kind == DN_LABELS) && (b->kind == DN_NUMS || b->kind == DN_LABELS)) {
        int w = a->kind == DN_NUMS ? a->width : 1;
        double *u = NULL, *v = NULL;
        size_t nu = 0, nv = 0;
        int ok = dict_node_scalars(a, w, &u, &nu, &e) == 0 && dict_node_scalars(b, w, &v, &nv, &e) == 0 &&
                 nu == nv && memcmp(u, v, nu * (size_t)w * sizeof(double)) == 0;
        free(u);
        free(v);
        return ok;
    }
    if (a->kind != b->kind || a->n != b->n) return 0;
    switch (a->kind) {
    case DN_WORD:
    case DN_STRING:
    case DN_PUNCT:
        return strcmp(a->text, b->text) == 0;
    case DN_NUMBER:
        return a->num == b->num && a->is_int == b->is_int;
    case DN_DICT:
        return same_dict(a->dict, b->dict);
    case DN_RAGGED:
        return memcmp(a->off, b->off, (a->n + 1) * sizeof(int)) == 0 &&
               memcmp(a->iv, b->iv, (size_t)a->off[a->n] * sizeof(int)) == 0;
    default:
        for (size_t i = 0; i < a->n; i++)
            if (!same_node(a->items[i], b->items[i])) return 0;
        return 1;
    }
}

static const char roundtrip_text[] =
    "FoamFile { version 2.0; format ascii; class volVectorField; object U; }\n"
    "dimensions [0 1 -1 0 0 0 0];\n"
    "internalField nonuniform List<vector> 12((0 0 0) (0.005 1e-300 -2) (1 2 3) (1 2 3) (1 2 3) (1 2 3)\n"
    "  (1 2 3) (1 2 3) (1 2 3) (1 2 3) (1 2 3) (0.1 0.2 0.30000000000000004));\n"
    "title \"quote \\\" and \\\\ backslash\";\n"
    "\"(U|k)Final\" { relTol 0; }\n"
    "boundaryField\n{\n    inlet { type fixedValue; value uniform (1 0 0); }\n"
    "    wall { type noSlip; inGroups 1(wall); f 2(4(1 2 3 4) 3(5 6 7)); }\n"
    "    out { value nonuniform 0(); }\n}\n"
    "grading (4 4 4 4 ((2 4 1) (1 3 0.3)) 1 1 ((2 4 1) (1 3 0.3)) 1 1 1 1);\n"
    "blocks ( hex (0 1 2 3 4 5 6 7) (20 20 1) simpleGrading (1 1 1) );\n"
    "patches ( a { x 1; } b { y (1 2); } );\n"
    "s 1.50;\nlong 1234567890123456789;\nempty;\nnumbers (1.0 2.0 3.5 4 5 6 7 8 9 10 11 12);\n"
    "\"\" a b;\n\"\";\n"
    "ow (x h(scalar= );\n"
    "rag ((0 0 0) (1 0 0) (1 1 0) (1e1 10 9) (12 13 14 15));\n"
    "negz (1 -0 2);\nnegzf (1 -0 2.5 3 4 5 6 7 8 9 10 11);\nu 2{(0 -0 1)};\n";

TEST(round_trip)
{
    Err e;
    Dict *a = parse(roundtrip_text, &e);
    EXPECT(a, "%s", e.msg);
    if (!a) return;
    Buf w1;
    buf_init(&w1);
    dict_write(a, &w1);
    Dict *b = dict_parse(w1.p, w1.n, "written", &e);
    EXPECT(b, "written text does not parse: %s\n%s", e.msg, w1.p);
    if (b) {
        EXPECT(same_dict(a, b), "trees differ after write/parse:\n%s", w1.p);
        Buf w2;
        buf_init(&w2);
        dict_write(b, &w2);
        EXPECT(w1.n == w2.n && memcmp(w1.p, w2.p, w1.n) == 0, "second write differs:\n%s\n---\n%s", w1.p, w2.p);
        buf_free(&w2);
        dict_free(b);
    }
    CONTAINS(w1.p, "dimensions      [0 1 -1 0 0 0 0];\n");
    CONTAINS(w1.p, "boundaryField\n{\n    inlet\n    {\n        type            fixedValue;\n"
                   "        value           uniform (1 0 0);\n    }\n");
    CONTAINS(w1.p, "internalField   nonuniform List<vector> \n12\n(\n(0 0 0)\n(0.005 1e-300 -2)\n");
    CONTAINS(w1.p, "(0.1 0.2 0.30000000000000004)\n)\n;\n");
    CONTAINS(w1.p, "\"(U|k)Final\"\n{\n");
    CONTAINS(w1.p, "value           nonuniform 0();");
    CONTAINS(w1.p, "s               1.50;");
    buf_free(&w1);
    dict_free(a);
}

TEST(build_and_write)
{
    Err e;
    Dict *d = dict_new("built");
    EXPECT(dict_set(d, "a", "uniform (0 0 0)", &e) == 0, "%s", e.msg);
    EXPECT(dict_set(d, "nFaces", "20", &e) == 0, "%s", e.msg);
    Dict *s = dict_add_subdict(d, "sub");
    EXPECT(dict_add_subdict(d, "sub") == s, "existing sub-dictionary returned");
    EXPECT(dict_set(s, "veryLongKeywordName", "2(a b);", &e) == 0, "%s", e.msg);
    EXPECT(dict_set(d, "nFaces", "21", &e) == 0, "replace");
    EXPECT(dict_set(d, "bad", "(1 2", &e) < 0, "bad value");
    CONTAINS(e.msg, "unterminated list");
    EXPECT(strcmp(write_text(d), "a               uniform (0 0 0);\n\nnFaces          21;\n\nsub\n{\n"
                                 "    veryLongKeywordName (a b);\n}\n") == 0,
           "'%s'", write_text(d));
    Buf body;
    buf_init(&body);
    dict_write_body(d, &body, 4);
    EXPECT(strcmp(body.p, "    a               uniform (0 0 0);\n    nFaces          21;\n    sub\n    {\n"
                          "        veryLongKeywordName (a b);\n    }\n") == 0,
           "body '%s'", body.p);
    buf_free(&body);
    EXPECT(dict_remove(d, "a") == 1 && dict_remove(d, "a") == 0 && d->n == 2, "remove");
    Buf b;
    buf_init(&b);
    dict_write_node(value_of(d, "nFaces"), &b);
    EXPECT(strcmp(b.p, "21") == 0, "node '%s'", b.p);
    buf_free(&b);
    dict_free(d);
}

/* ---- keyword checking ---- */

TEST(check_keys)
{
    static const DictKey keys[] = {{"application", NULL, "solver"},
                                   {"endTime", NULL, "end"},
                                   {"deltaT", "1", "step"},
                                   {"writeInterval", "1", "interval"},
                                   {NULL, NULL, NULL}};
    Err e;
    Dict *d = parse("FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\napplication x;\nendTme 1;\n", &e);
    EXPECT(d && dict_check_keys(d, keys, &e) < 0, "typo found");
    EXPECT(strcmp(e.msg, "test.dict:3: unknown keyword 'endTme' in test.dict; did you mean 'endTime'?") == 0, "%s",
           e.msg);
    dict_free(d);
    d = parse("application x;\ncompletelyDifferent 1;\n", &e);
    EXPECT(d && dict_check_keys(d, keys, &e) < 0, "unknown key");
    CONTAINS(e.msg, "test.dict:2: unknown keyword 'completelyDifferent' in test.dict; valid keywords: application endTime deltaT writeInterval");
    dict_free(d);
    d = parse("application x;\n\n3 endTime;\n", &e);
    EXPECT(d && dict_check_keys(d, keys, &e) < 0, "value without keyword");
    EXPECT(strcmp(e.msg, "test.dict:3: value without a keyword in dictionary 'test.dict'") == 0, "%s", e.msg);
    dict_free(d);
    d = parse("application x;\ndeltaT 1;\n", &e);
    EXPECT(d && dict_check_keys(d, keys, &e) == 0, "all known");
    dict_free(d);
    static const char *const c[] = {"deltaT", "endTime", "writeInterval"};
    EXPECT(dict_closest("writeIntervl", c, 3) == c[2], "closest");
    EXPECT(dict_closest("DeltaT", c, 3) == c[0], "case differs");
    EXPECT(dict_closest("xyz", c, 3) == NULL, "nothing close");
}

/* ---- robustness ---- */

TEST(every_prefix_and_mutations)
{
    size_t n = strlen(roundtrip_text);
    char *t = malloc(n + 1);
    int parsed = 0, failed_silently = 0;
    for (size_t k = 0; k <= n; k++) {
        Err e;
        e.msg[0] = '\0';
        Dict *d = dict_parse(roundtrip_text, k, "prefix", &e);
        if (d) parsed++;
        else if (!e.msg[0]) failed_silently++;
        dict_free(d);
    }
    EXPECT(failed_silently == 0, "%d prefixes failed without a message", failed_silently);
    EXPECT(parsed > 10, "some prefixes parse (%d)", parsed);
    uint64_t r = 12345;
    static const char bytes[] = "(){}[];\"$#/*\\ \n0123456789.-eE\0xyz<>";
    for (int it = 0; it < 3000; it++) {
        memcpy(t, roundtrip_text, n);
        for (int m = 0; m < 1 + it % 4; m++) {
            r = r * 6364136223846793005ull + 1442695040888963407ull;
            t[(r >> 33) % n] = bytes[(r >> 20) % (sizeof bytes - 1)];
        }
        Err e;
        e.msg[0] = '\0';
        Dict *d = dict_parse(t, n, "mutant", &e);
        if (!d && !e.msg[0]) failed_silently++;
        if (!d && !e.msg[0] && failed_silently == 1) printf("  silent failure on:\n%.*s\n", (int)n, t);
        if (d) {
            Buf w;
            buf_init(&w);
            dict_write(d, &w);
            Dict *d2 = dict_parse(w.p ? w.p : "", w.n, "mutant", &e);
            if (!d2) {
                if (failed_silently < 1000) printf("  written text does not parse: %s\n%s\n", e.msg, w.p);
                failed_silently += 1000;
            }
            dict_free(d2);
            buf_free(&w);
        }
        dict_free(d);
    }
    EXPECT(failed_silently == 0, "mutants: %d failures", failed_silently);
    free(t);
    /* deep nesting is refused, not a stack overflow */
    size_t depth = 100000;
    char *deep = malloc(2 * depth + 8);
    memcpy(deep, "a ", 2);
    memset(deep + 2, '(', depth);
    deep[2 + depth] = '\0';
    Err e;
    Dict *d = dict_parse(deep, 2 + depth, "deep", &e);
    EXPECT(!d && strstr(e.msg, "deep:1: nesting deeper than 64 levels"), "%s", d ? "parsed" : e.msg);
    for (size_t k = 0; k < depth; k++) deep[k] = k % 2 ? '{' : 'b';
    d = dict_parse(deep, depth, "deep", &e);
    EXPECT(!d && strstr(e.msg, "nesting deeper than 64 levels"), "%s", d ? "parsed" : e.msg);
    free(deep);
    /* variables that double at every line are stopped, not exponential */
    Buf x;
    buf_init(&x);
    buf_puts(&x, "v0 (1 2 3 4 5 6 7 8 9 10);\n");
    for (int k = 1; k < 40; k++) buf_printf(&x, "v%d $v%d $v%d;\n", k, k - 1, k - 1);
    d = dict_parse(x.p, x.n, "grow", &e);
    EXPECT(!d && strstr(e.msg, "expansions copy too much data"), "%s", d ? "parsed" : e.msg);
    buf_clear(&x);
    buf_puts(&x, "a0 { x 1; }\n");
    for (int k = 1; k < 300; k++) buf_printf(&x, "a%d { b $a%d; }\n", k, k - 1);
    d = dict_parse(x.p, x.n, "nest", &e);
    EXPECT(!d && strstr(e.msg, "nesting deeper than 256 levels"), "%s", d ? "parsed" : e.msg);
    buf_free(&x);
}

/* ---- speed ---- */

TEST(big_list_speed)
{
#if defined(__SANITIZE_ADDRESS__)
    size_t n = 1000000;
#else
    size_t n = 10000000;
#endif
    Buf b;
    buf_init(&b);
    buf_printf(&b, "internalField nonuniform List<scalar>\n%zu\n(\n", n);
    uint64_t r = 88172645463325252ull;
    char s[40];
    for (size_t i = 0; i < n; i++) {
        r ^= r << 13;
        r ^= r >> 7;
        r ^= r << 17;
        int k = foam_fmt_double(s, (double)(r >> 11) / 9007199254740992.0 * 10 - 5, 6);
        s[k++] = '\n';
        buf_put(&b, s, (size_t)k);
    }
    buf_puts(&b, ");\n");
    clock_t c0 = clock();
    Err e;
    Dict *d = dict_parse(b.p, b.n, "big", &e);
    double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
    const DictNode *nd = d ? value_of(d, "internalField") : NULL;
    EXPECT(nd && nd->kind == DN_NUMS && nd->n == n, "%s", d ? "wrong list" : e.msg);
    printf("  dict_parse: %zu scalars, %.1f MB in %.3f s CPU = %.0f MB/s\n", n, (double)b.n / 1e6, cpu,
           (double)b.n / 1e6 / (cpu > 0 ? cpu : 1e-9));
    dict_free(d);
    buf_free(&b);
}

int main(void)
{
    RUN(controldict_values);
    RUN(typed_lookup_errors);
    RUN(lists_and_compaction);
    RUN(general_path_equals_fast_path);
    RUN(size_then_list_on_one_line);
    RUN(dimensions_and_uniform);
    RUN(boundary_list_of_dicts);
    RUN(regex_keys);
    RUN(variables);
    RUN(merge_and_replace);
    RUN(includes);
    RUN(unsupported_directives);
    RUN(parse_errors_exact);
    RUN(header_checks);
    RUN(list_sizes_everywhere);
    RUN(binary_lists);
    RUN(gzip_read);
    RUN(round_trip);
    RUN(build_and_write);
    RUN(check_keys);
    RUN(every_prefix_and_mutations);
    RUN(big_list_speed);
    return test_summary();
}
