/* etc/sanitize/lsan.c: LeakSanitizer hooks, linked only into sanitizer
 * builds (make SANITIZE=1, make fuzz), never into the library.
 *
 * gmsh's mesher and OpenCASCADE keep allocations past gmshFinalize;
 * programs that use common/cad.c would fail under LeakSanitizer on those.
 * The sanitizer runtime reads this hook at exit.  The patterns match only
 * frames inside OpenCASCADE (libTK*), gmsh's surface mesher and its .geo
 * parser, so a gmsh array that cad.c forgets to gmshFree is still
 * reported.  OpenMPI, which PETSc starts (fv/linsolve.c), keeps its
 * start-up allocations past MPI_Finalize in its own libraries and the
 * components it loads and unloads (libmpi, libopen-pal, libopen-rte,
 * hwloc, pmix, mca_*); those frames are matched too, never PETSc's or
 * ours, so a KSP or Mat that linsolve forgets to destroy is reported.
 * The second hook keeps the sanitizer from listing the
 * suppressions it used on stderr, which tool tests read. */

const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libTK\nleak:meshGFace\nleak:strsave\n"
           "leak:libmpi.so\nleak:libopen-pal\nleak:libopen-rte\nleak:libhwloc\nleak:libpmix\nleak:libevent\nleak:mca_\n";
}

const char *__lsan_default_options(void);
const char *__lsan_default_options(void) { return "print_suppressions=0"; }
