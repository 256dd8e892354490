/* oitbench bus: the host-to-device rate of this GL, measured as the
 * streamer moves bytes (bench_bus.c). */
#ifndef OIT_OITBENCH_BENCH_BUS_H
#define OIT_OITBENCH_BENCH_BUS_H

/* argv[1] is "bus"; prints one JSON object to stdout; returns the exit code. */
int oit_bench_bus_main(int argc, char **argv);

#endif
