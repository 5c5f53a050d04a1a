/* measure.h: `oit measure`, the source's measuring command line (thesis
 * appendix E.3): one result line appended to a results file per run. */
#ifndef OIT_CLI_MEASURE_H
#define OIT_CLI_MEASURE_H

int command_measure(int argc, char **argv);

#endif
