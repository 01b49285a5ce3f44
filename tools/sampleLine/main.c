/*
** sampleLine: samples fields along straight lines into CSV files, from
** system/sampleLineDict.  See doc/tools/sampleLine.md and common/sampleline.h
** (the dictionary and the CSV columns).
**
** Output: postProcessing/sampleLine/<time>/<line>.csv, or under -o DIR;
** with "-o -", the same CSV on stdout (banner and log on stderr).  The
** dictionary, every line and every field are checked before anything is
** written.
*/
#include "args.h"
#include "err.h"
#include "sampleline.h"
#include "locate.h"
#include "mem.h"
#include "mesh.h"
#include "runtime.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const ArgOpt opts[] = {
    {"-o", "DIR", "output directory (default: postProcessing/sampleLine); '-' = CSV to stdout"},
    {"-line", "NAME", "sample only this line"},
    {0}};

static const ArgDict dicts[] = {{"system/sampleLineDict", sampleline_keys, sampleline_help}, {0}};

static const ToolInfo tool = {"sampleLine", "samples fields along lines to CSV", opts, dicts, 1};

int main(int argc, char **argv)
{
    Args a;
    Err e;
    args_parse(argc, argv, &tool, &a);
    if (a.argc) err_fatal("unexpected argument '%s'", a.argv[0]);
    const char *o = args_get(&a, &tool, "-o");
    int to_stdout = o && !strcmp(o, "-");
    if (to_stdout) args_info_to_stderr(&a);
    args_banner(&a, &tool);

    char *dpath = a.dict ? mem_strdup(a.dict) : args_case_path(&a, "system/sampleLineDict");
    Dict *d = dict_read(dpath, &e);
    SampleLineDict s;
    if (!d || sampleline_parse(&s, d, &e)) err_die(&e);
    const char *only = args_get(&a, &tool, "-line");
    if (only && sampleline_pick(&s, only, &e)) err_fatal("%s", e.msg);

    TimeSel ts;
    int nt = runtime_select_case(&ts, a.case_dir, a.time_spec, a.latest, a.nozero, &e);
    if (nt < 0) err_die(&e);
    if (nt == 0) err_fatal("%s: no time directory selected", a.case_dir);

    Mesh m;
    char *mpath = args_case_path(&a, "constant/polyMesh");
    if (mesh_read(&m, mpath, &e)) err_die(&e);
    mesh_cell_faces(&m);
    mesh_geometry(&m);
    Locator L;
    locate_build(&L, &m);

    char *outdir = to_stdout ? NULL : o ? mem_strdup(o) : args_case_path(&a, "postProcessing/sampleLine");
    Buf log;
    buf_init(&log);
    for (int i = 0; i < nt; i++) {
        const char *time = runtime_sel_time(&ts, i)->name;
        log_time(&a, time);
        SampleLineTime lt;
        int rc = sampleline_time_begin(&lt, &s, &m, &L, a.case_dir, time, outdir, nt * s.nlines, &e);
        for (int j = 0; j < s.nlines && !rc; j++) {
            rc = sampleline_time_sample(&lt, &s.lines[j], &log, &e);
            fwrite(log.p, 1, log.n, a.info);
            buf_clear(&log);
        }
        fprintf(a.info, "\n");
        sampleline_time_end(&lt);
        if (rc) err_die(&e);
    }

    log_exec(&a);
    log_end(&a);
    buf_free(&log);
    free(outdir);
    locate_free(&L);
    mesh_free(&m);
    runtime_free_sel(&ts);
    sampleline_free(&s);
    dict_free(d);
    free(mpath);
    free(dpath);
    args_free(&a);
    return 0;
}
