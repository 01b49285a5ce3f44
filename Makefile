# Kiesel: top-level build.
#
#   make            build common/libkiesel.a and every tool into bin/
#   make test       install missing dependencies, build, run the test suite
#   make bench      benchmarks (results: doc/performance.md)
#   make fuzz       fuzz the readers (FUZZ_SECONDS per target, default 600)
#   make validate   longer validation studies
#   make SANITIZE=1 ...   the same with AddressSanitizer + UBSan (build/asan)
#
# Layout: common/*.c -> $(B)/libkiesel.a; tools/<name>/*.c -> $(BIN)/<name>;
# tests/common/test_*.c -> $(B)/tests/test_*.

CC      ?= gcc
CSTD    := -std=c11 -D_POSIX_C_SOURCE=200809L
WARN    := -Wall -Wextra
OPT     ?= -O2 -g
LDLIBS  := -lgmsh -lgsl -lgslcblas -lz -lm

ifeq ($(SANITIZE),1)
  B      := build/asan
  BIN    := build/asan/bin
  OPT    := -O1 -g -fno-omit-frame-pointer
  SAN    := -fsanitize=address,undefined -fno-sanitize-recover=undefined
else
  B      := build/release
  BIN    := bin
  SAN    :=
endif

CFLAGS  := $(CSTD) $(WARN) $(OPT) $(SAN) -Icommon
LDFLAGS := $(SAN)

LIB_SRC  := $(wildcard common/*.c)
LIB_OBJ  := $(patsubst common/%.c,$(B)/common/%.o,$(LIB_SRC))
LIB      := $(B)/libkiesel.a

TOOLS    := $(notdir $(patsubst %/,%,$(dir $(wildcard tools/*/main.c))))
TOOL_BIN := $(addprefix $(BIN)/,$(TOOLS))

TEST_SRC := $(wildcard tests/common/test_*.c)
TEST_BIN := $(patsubst tests/common/%.c,$(B)/tests/%,$(TEST_SRC))

FUZZ_SRC := $(wildcard tests/fuzz/fuzz_*.c)

.PHONY: all test check bench fuzz validate clean deps tutorial
.SECONDARY:
all: $(TOOL_BIN) $(TEST_BIN)

$(B)/common/%.o: common/%.c $(wildcard common/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@

$(LIB): $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(B)/tools/%.o: tools/%.c $(wildcard common/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@

tool_objs = $(patsubst tools/%.c,$(B)/tools/%.o,$(wildcard tools/$(1)/*.c))

.SECONDEXPANSION:
$(BIN)/%: $$(call tool_objs,$$*) $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) $(filter %.o,$^) $(LIB) $(LDLIBS) -o $@

$(B)/tests/%: tests/common/%.c tests/test.h tests/fixture.h tests/randgeo.h $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Itests $< $(LIB) $(LDLIBS) -o $@

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

bench: all
	@KIESEL_BIN=$(abspath $(BIN)) bench/run

validate: all
	@KIESEL_BIN=$(abspath $(BIN)) tests/run --validate

fuzz:
	@tests/fuzz/run $(FUZZ_SECONDS)

clean:
	rm -rf build bin
