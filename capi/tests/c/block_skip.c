/*
 * Block skip toggled through the C ABI while a program runs:
 *
 *   block_skip PROGRAM.gbc
 *
 * Starts with every block-skip switch as the reference machine has it
 * (on), runs the program ahead once, then turns switch 1 off and runs the
 * program to its end. Prints the source line of every period's set point
 * (the block the axes are executing), one per line. Exit status: 0 at the
 * program's end, 1 on any failure.
 */
#include <stdio.h>
#include <stdlib.h>

#include "gbc.h"

static int fail(const char *what, GbcStatus s) {
    char msg[512];
    if (gbc_last_error(msg, sizeof msg, NULL) != GBC_STATUS_OK)
        msg[0] = 0;
    fprintf(stderr, "block_skip: %s failed (status %d): %s\n", what, (int)s, msg);
    return 1;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: block_skip PROGRAM.gbc\n");
        return 1;
    }
    FILE *f = fopen(argv[1], "rb");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    static unsigned char program[1 << 16];
    size_t len = fread(program, 1, sizeof program, f);
    fclose(f);
    if (len == 0 || len == sizeof program) {
        fprintf(stderr, "block_skip: %s: empty or too large\n", argv[1]);
        return 1;
    }

    GbcMachine machine = 0;
    GbcStatus s = gbc_machine_reference(&machine);
    if (s != GBC_STATUS_OK)
        return fail("machine", s);
    GbcController ctl = 0;
    s = gbc_controller_new(machine, NULL, &ctl);
    gbc_machine_free(machine);
    if (s != GBC_STATUS_OK)
        return fail("controller", s);
    if ((s = gbc_controller_load(ctl, program, len)) != GBC_STATUS_OK) {
        gbc_controller_free(ctl);
        return fail("load", s);
    }

    int status = 0;
    gbc_cycle_start(ctl);
    for (unsigned long period = 0; period < 10000000UL; period++) {
        if ((s = gbc_run_ahead(ctl)) != GBC_STATUS_OK) {
            status = fail("run ahead", s);
            break;
        }
        if (period == 0 && (s = gbc_set_block_skip(ctl, 1, false)) != GBC_STATUS_OK) {
            status = fail("block skip", s);
            break;
        }
        GbcSetPoint sp;
        if ((s = gbc_tick(ctl, &sp)) != GBC_STATUS_OK) {
            status = fail("tick", s);
            break;
        }
        printf("%u\n", sp.line);
        GbcStateInfo st;
        if ((s = gbc_state(ctl, &st)) != GBC_STATUS_OK) {
            status = fail("state", s);
            break;
        }
        if (st.state == GBC_RUN_STATE_ENDED)
            break;
        if (st.state != GBC_RUN_STATE_RUNNING) {
            fprintf(stderr, "block_skip: state %d\n", (int)st.state);
            status = 1;
            break;
        }
    }
    gbc_controller_free(ctl);
    return status;
}
