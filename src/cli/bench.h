/* bench.h: `oit bench` (scenes x algorithms x sizes, CSV and JSON) and
 * `oit measure` (the source's measuring command line). docs/cli.md, docs/benchmarks.md. */
#ifndef OIT_CLI_BENCH_H
#define OIT_CLI_BENCH_H

int command_bench(int argc, char **argv);
int command_measure(int argc, char **argv);

#endif
