# Kiesel: top-level build.
#
#   make            build common/libkiesel.a and every tool into bin/
#   make test       install missing dependencies, build, run the test suite
#   make bench      benchmarks (results: doc/performance.md)
#   make fuzz       fuzz the readers (FUZZ_SECONDS per target, default 600)
#   make validate   longer validation studies
#   make SANITIZE=1 ...   the same with AddressSanitizer + UBSan (build/asan)
#
# Layout (doc/architecture.md): common/*.c -> $(B)/libkiesel.a, the library;
# fv/*.c -> $(B)/libkieselfv.a, the finite-volume layer above it (PETSc);
# app/*.c -> $(B)/libkieselapp.a, the application frame above both (only
# the frame prints and exits); tools/<name>/*.c -> $(BIN)/<name>, linked
# with all three; tests/{common,fv,app}/test_*.c -> $(B)/tests/test_*.
# common/ is compiled with -Icommon only, fv/ with -Icommon -Ifv, so
# neither can include a layer above it.

# CC is set, not defaulted: make's built-in CC is cc, so ?= never applied.
# `make CC=clang` still overrides it.
CC      := gcc
CSTD    := -std=c11 -D_POSIX_C_SOURCE=200809L
WARN    := -Wall -Wextra -Wshadow -Wmissing-prototypes -Wstrict-prototypes \
           -Wundef -Wwrite-strings -Wredundant-decls
DEPFLAGS = -MMD -MP
OPT     ?= -O2 -g
LDLIBS  := -lgmsh -lgsl -lgslcblas -lz -lm

ifeq ($(SANITIZE),1)
  B      := build/asan
  BIN    := build/asan/bin
  OPT    := -O1 -g -fno-omit-frame-pointer
  SAN    := -fsanitize=address,undefined -fno-sanitize-recover=undefined
  # LeakSanitizer's hooks (gmsh's own leaks) are linked only here
  SAN_OBJ := $(B)/etc/sanitize/lsan.o
else
  B      := build/release
  BIN    := bin
  SAN    :=
  SAN_OBJ :=
endif

# PETSc (and the MPI it is built with) for the finite-volume layer's linear
# solves; its headers as system headers, so our warning flags judge only
# our code.  Linked --as-needed: the grid tools do not load MPI.
PETSC_PC    := PETSc mpi
PETSC_CFLAGS := $(patsubst -I%,-isystem %,$(filter -I%,$(shell pkg-config --cflags $(PETSC_PC) 2>/dev/null)))
PETSC_LIBS  := $(shell pkg-config --libs $(PETSC_PC) 2>/dev/null)

CFLAGS  := $(CSTD) $(WARN) $(OPT) $(SAN) -Icommon
FVFLAGS := $(CFLAGS) -Ifv $(PETSC_CFLAGS)
APPFLAGS := $(FVFLAGS) -Iapp
LDFLAGS := $(SAN)
LDLIBS_ALL := -Wl,--as-needed $(LDLIBS) $(PETSC_LIBS)

LIB_SRC  := $(wildcard common/*.c)
LIB_OBJ  := $(patsubst common/%.c,$(B)/common/%.o,$(LIB_SRC))
LIB      := $(B)/libkiesel.a

FV_SRC   := $(wildcard fv/*.c)
FV_OBJ   := $(patsubst fv/%.c,$(B)/fv/%.o,$(FV_SRC))
FVLIB    := $(B)/libkieselfv.a

APP_SRC  := $(wildcard app/*.c)
APP_OBJ  := $(patsubst app/%.c,$(B)/app/%.o,$(APP_SRC))
APPLIB   := $(B)/libkieselapp.a

TOOLS    := $(notdir $(patsubst %/,%,$(dir $(wildcard tools/*/main.c))))
TOOL_BIN := $(addprefix $(BIN)/,$(TOOLS))

TEST_SRC := $(wildcard tests/common/test_*.c)
TEST_BIN := $(patsubst tests/common/%.c,$(B)/tests/%,$(TEST_SRC))
APPTEST_SRC := $(wildcard tests/app/test_*.c)
APPTEST_BIN := $(patsubst tests/app/%.c,$(B)/tests/%,$(APPTEST_SRC))
FVTEST_SRC := $(wildcard tests/fv/test_*.c)
FVTEST_BIN := $(patsubst tests/fv/%.c,$(B)/tests/%,$(FVTEST_SRC))

# the manufactured-solution study of make validate (tests/validation/mms):
# a program over the finite-volume layer and solveGranular's model
MMS_SRC  := $(wildcard tests/validation/mms/*.c)
MMS_OBJ  := $(patsubst tests/%.c,$(B)/tests/%.o,$(MMS_SRC))
MMS_BIN  := $(B)/tests/mms

FUZZ_SRC := $(wildcard tests/fuzz/fuzz_*.c)

.PHONY: all test check bench fuzz validate clean deps tutorial
.SECONDARY:
all: $(TOOL_BIN) $(TEST_BIN) $(APPTEST_BIN) $(FVTEST_BIN) $(FVLIB) $(MMS_BIN)

$(B)/common/%.o: common/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(DEPFLAGS) -c $< -o $@

$(B)/etc/sanitize/%.o: etc/sanitize/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(DEPFLAGS) -c $< -o $@

$(LIB): $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(B)/fv/%.o: fv/%.c
	@mkdir -p $(dir $@)
	$(CC) $(FVFLAGS) $(DEPFLAGS) -c $< -o $@

$(FVLIB): $(FV_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(B)/app/%.o: app/%.c
	@mkdir -p $(dir $@)
	$(CC) $(APPFLAGS) $(DEPFLAGS) -c $< -o $@

$(APPLIB): $(APP_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(B)/tools/%.o: tools/%.c
	@mkdir -p $(dir $@)
	$(CC) $(APPFLAGS) $(DEPFLAGS) -c $< -o $@

tool_objs = $(patsubst tools/%.c,$(B)/tools/%.o,$(wildcard tools/$(1)/*.c))

.SECONDEXPANSION:
$(BIN)/%: $$(call tool_objs,$$*) $(APPLIB) $(FVLIB) $(LIB) $(SAN_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) $(filter %.o,$^) $(APPLIB) $(FVLIB) $(LIB) $(LDLIBS_ALL) -o $@

$(B)/tests/%: tests/common/%.c $(LIB) $(SAN_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(DEPFLAGS) -MF $@.d -Itests $< $(SAN_OBJ) $(LIB) $(LDLIBS) -o $@

# tests of the finite-volume layer: the same, with fv/ and libkieselfv.a
$(B)/tests/%: tests/fv/%.c $(FVLIB) $(LIB) $(SAN_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $(FVFLAGS) $(DEPFLAGS) -MF $@.d -Itests $< $(SAN_OBJ) $(FVLIB) $(LIB) $(LDLIBS_ALL) -o $@

# tests of the frame: the same, with app/ and libkieselapp.a
$(B)/tests/%: tests/app/%.c $(APPLIB) $(FVLIB) $(LIB) $(SAN_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $(APPFLAGS) $(DEPFLAGS) -MF $@.d -Itests $< $(SAN_OBJ) $(APPLIB) $(FVLIB) $(LIB) $(LDLIBS_ALL) -o $@

# the study: its files with the fv layer's flags, linked with the model
$(B)/tests/validation/mms/%.o: tests/validation/mms/%.c
	@mkdir -p $(dir $@)
	$(CC) $(FVFLAGS) $(DEPFLAGS) -Itests -Itools/solveGranular -c $< -o $@

$(MMS_BIN): $(MMS_OBJ) $(B)/tools/solveGranular/newtonian.o $(B)/tools/solveGranular/granular.o $(B)/tools/solveGranular/restprofile.o $(FVLIB) $(LIB) $(SAN_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) $(filter %.o,$^) $(FVLIB) $(LIB) $(LDLIBS_ALL) -o $@

# Header dependencies, generated by the compiler (-MMD -MP) at each build.
-include $(wildcard $(B)/common/*.d $(B)/fv/*.d $(B)/app/*.d $(B)/tools/*/*.d $(B)/tests/*.d $(B)/tests/validation/*/*.d $(B)/etc/sanitize/*.d)

deps:
	@etc/install-deps

# The README's test command: set-up, build, run everything.
test: deps
	@$(MAKE) --no-print-directory all
	@KIESEL_BIN=$(abspath $(BIN)) KIESEL_TESTBIN=$(abspath $(B)/tests) tests/run

check: all
	@KIESEL_BIN=$(abspath $(BIN)) KIESEL_TESTBIN=$(abspath $(B)/tests) tests/run

tutorial: deps
	@$(MAKE) --no-print-directory all
	@tutorials/basic/quickStart/Allrun
	@tutorials/granular/cylinderFlow/Allrun
	@tutorials/granular/rotatingDisc/Allrun

bench: all
	@KIESEL_BIN=$(abspath $(BIN)) bench/run
	@KIESEL_BIN=$(abspath $(BIN)) bench/bench_solver
	@KIESEL_BIN=$(abspath $(BIN)) bench/bench_openfoam

validate: all
	@KIESEL_BIN=$(abspath $(BIN)) tests/run --validate

fuzz:
	@tests/fuzz/run $(FUZZ_SECONDS)

clean:
	rm -rf build bin
