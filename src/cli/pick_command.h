/* pick_command.h: `oit pick`, what one pixel of a render shows, part by part
 * (oit_pick_pixel; docs/cli.md, "oit pick"). */
#ifndef OIT_CLI_PICK_COMMAND_H
#define OIT_CLI_PICK_COMMAND_H

int command_pick(int argc, char **argv);

#endif
