/*
 * A controller split across two threads through the C ABI:
 *
 *   split PROGRAM.gbc
 *
 * Loads the program on the reference machine and splits the controller:
 * a POSIX thread calls gbc_run_ahead on the interpreter half until told
 * to stop, while the main thread ticks the real-time half to the
 * program's end. Prints the last set point, "X Z COUNT_X COUNT_Z", and on
 * stderr the periods the motion stood starved for lack of commands.
 * Exit status: 0 at the program's end, 1 on any failure.
 */
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdio.h>

#include "gbc.h"

static atomic_bool stop_interpreter;
static atomic_int interpreter_status;

static int fail(const char *what, GbcStatus s) {
    char msg[512];
    if (gbc_last_error(msg, sizeof msg, NULL) != GBC_STATUS_OK)
        msg[0] = 0;
    fprintf(stderr, "split: %s failed (status %d): %s\n", what, (int)s, msg);
    return 1;
}

/* The ordinary thread: runs the VM ahead of the motion. */
static void *interpreter(void *arg) {
    GbcController interp = *(GbcController *)arg;
    while (!atomic_load(&stop_interpreter)) {
        GbcStatus s = gbc_run_ahead(interp);
        if (s != GBC_STATUS_OK) {
            atomic_store(&interpreter_status, (int)s);
            break;
        }
        sched_yield();
    }
    return NULL;
}

/* The real-time thread's work: one period after another to the end. */
static int tick_to_end(GbcController rt) {
    GbcSetPoint sp;
    unsigned long starved = 0;
    for (unsigned long period = 0; period < 100000000UL; period++) {
        GbcStatus s = gbc_tick(rt, &sp);
        if (s != GBC_STATUS_OK)
            return fail("tick", s);
        GbcStateInfo st;
        if ((s = gbc_state(rt, &st)) != GBC_STATUS_OK)
            return fail("state", s);
        if (st.state == GBC_RUN_STATE_ENDED) {
            printf("%.6f %.6f %lld %lld\n", sp.x, sp.z, (long long)sp.count_x,
                   (long long)sp.count_z);
            fprintf(stderr, "split: %lu periods starved\n", starved);
            return 0;
        }
        if (st.state == GBC_RUN_STATE_ALARM) {
            fprintf(stderr, "split: alarm %u\n", st.alarm_code);
            return 1;
        }
        if (st.state == GBC_RUN_STATE_STARVED) {
            starved++;
            sched_yield();
        }
    }
    fprintf(stderr, "split: the program did not end\n");
    return 1;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: split PROGRAM.gbc\n");
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
        fprintf(stderr, "split: %s: empty or too large\n", argv[1]);
        return 1;
    }

    GbcMachine machine = 0;
    GbcStatus s = gbc_machine_reference(&machine);
    if (s != GBC_STATUS_OK)
        return fail("machine", s);
    GbcController interp = 0;
    s = gbc_controller_new(machine, NULL, &interp);
    gbc_machine_free(machine);
    if (s != GBC_STATUS_OK)
        return fail("controller", s);
    GbcController rt = 0;
    if ((s = gbc_controller_load(interp, program, len)) != GBC_STATUS_OK ||
        (s = gbc_controller_split(interp, &rt)) != GBC_STATUS_OK) {
        gbc_controller_free(interp);
        return fail("load and split", s);
    }

    pthread_t thread;
    if (pthread_create(&thread, NULL, interpreter, &interp) != 0) {
        fprintf(stderr, "split: no thread\n");
        gbc_realtime_free(rt);
        gbc_controller_free(interp);
        return 1;
    }
    int result = gbc_cycle_start(rt) == GBC_STATUS_OK ? tick_to_end(rt) : 1;
    atomic_store(&stop_interpreter, true);
    pthread_join(thread, NULL);
    if (atomic_load(&interpreter_status) != 0) {
        fprintf(stderr, "split: run-ahead failed (%d)\n", atomic_load(&interpreter_status));
        result = 1;
    }
    if (gbc_realtime_free(rt) != GBC_STATUS_OK || gbc_controller_free(interp) != GBC_STATUS_OK)
        result = 1;
    return result;
}
