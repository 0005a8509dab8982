/*
 * A controller loop in C over libgbc: load a program (compiled by gbcc, or
 * G-code text the library compiles), tick it once per interpolation period
 * until it ends, and print one line per period in the format of
 * `gbvm run FILE --emit trace`
 * (time_s,x,z,spindle_rpm,feed,line,motion,tool,file).
 *
 *   controller PROGRAM.gbc|PROGRAM.nc [MACHINE.toml] > trace.csv
 *
 * The PLC completes every function at once and cycle start is pressed at
 * every stop, as gbvm's reference host does, so the two traces are the
 * same. #500-#999 live in an array here (a real controller keeps them in
 * non-volatile memory). Exit status: 0 at the program's end, 2 on an
 * alarm, 1 on any other failure.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gbc.h"

/* The host: what the PLC was asked, and the persistent variables. */
struct host {
    unsigned plc_functions;
    unsigned stores;
    double vars[GBC_PERSISTENT_COUNT];
};

static void plc_request(void *user, const GbcPlcFunction *f) {
    struct host *h = user;
    h->plc_functions++;
    (void)f;
}

static bool plc_done(void *user, const GbcPlcFunction *f) {
    (void)user;
    (void)f;
    return true; /* FIN at once */
}

static int32_t vars_load(void *user, double *vars) {
    struct host *h = user;
    memcpy(vars, h->vars, sizeof h->vars);
    return 0;
}

static int32_t vars_store(void *user, const double *vars) {
    struct host *h = user;
    memcpy(h->vars, vars, sizeof h->vars);
    h->stores++;
    return 0;
}

/* Reads a whole file; NULL on failure. */
static unsigned char *read_file(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    unsigned char *buf = NULL;
    size_t cap = 0, n = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? 2 * cap : 65536;
            unsigned char *bigger = realloc(buf, cap);
            if (!bigger) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = bigger;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

/* A number as gbvm's trace prints it: d decimals, never "-0.000". */
static void put_fixed(double v, int d) {
    double half = 0.5 * pow(10.0, -d);
    if (fabs(v) < half || !isfinite(v))
        v = 0.0;
    printf("%.*f", d, v);
}

/* A CSV field as gbvm's trace prints it: quoted when it holds a comma,
 * a quote or a line end, a quote doubled inside. */
static void put_csv_field(const char *t) {
    if (!strpbrk(t, ",\"\n\r")) {
        fputs(t, stdout);
        return;
    }
    putchar('"');
    for (; *t; t++) {
        if (*t == '"')
            putchar('"');
        putchar(*t);
    }
    putchar('"');
}

/* The word of gbvm's trace for a kind of motion. */
static const char *motion_word(GbcMotion m) {
    switch (m) {
    case GBC_MOTION_RAPID:
        return "rapid";
    case GBC_MOTION_FEED:
        return "feed";
    case GBC_MOTION_THREAD:
        return "thread";
    case GBC_MOTION_ARC:
        return "arc";
    case GBC_MOTION_DWELL:
        return "dwell";
    case GBC_MOTION_NONE:
    default:
        return "none";
    }
}

static int fail(const char *what, GbcStatus s) {
    char msg[512];
    if (gbc_last_error(msg, sizeof msg, NULL) != GBC_STATUS_OK)
        msg[0] = 0;
    fprintf(stderr, "controller: %s failed (status %d): %s\n", what, (int)s, msg);
    return 1;
}

/* The codes in force, as a control's screen lists them (G00 G97 ... F S
 * T): those of the block the motion ran last. */
static void print_active(GbcController ctl) {
    GbcActiveCodes a;
    if (gbc_active_codes(ctl, &a) != GBC_STATUS_OK)
        return;
    fprintf(stderr, "controller: in force:");
    for (size_t i = 0; i < GBC_ACTIVE_GROUPS; i++) {
        unsigned g = a.g[i];
        if (g % 10)
            fprintf(stderr, " G%u.%u", g / 10, g % 10);
        else
            fprintf(stderr, " G%02u", g / 10);
    }
    fprintf(stderr, " F%g S%g T%04u\n", a.f, a.s, a.t);
}

/* W118 at run time: a thread whose block is too short for the axis to
 * reach (or leave) thread speed at the spindle speed the run really has.
 * Taking it allocates nothing; its text is made here, off the period
 * (a real controller would hand it to its screen's thread). */
static void report_room(GbcController ctl) {
    GbcRoomWarning w;
    while (gbc_take_room_warning(ctl, &w) == GBC_STATUS_OK && w.code != 0) {
        char file[256], text[256];
        if (gbc_file_name(ctl, w.file, file, sizeof file, NULL) != GBC_STATUS_OK)
            file[0] = 0;
        if (gbc_room_warning_text(&w, text, sizeof text, NULL) != GBC_STATUS_OK)
            text[0] = 0;
        fprintf(stderr, "%s:%u:%u: warning[W118]: %s\n", file, w.line, w.column, text);
    }
}

int main(int argc, char **argv) {
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: controller PROGRAM.gbc|PROGRAM.nc [MACHINE.toml]\n");
        return 1;
    }
    /* The library loaded must be the one this header describes. */
    if (gbc_abi_version() != GBC_ABI_VERSION) {
        fprintf(stderr, "controller: libgbc has ABI %u, gbc.h %u\n", gbc_abi_version(),
                (unsigned)GBC_ABI_VERSION);
        return 1;
    }
    size_t len = 0;
    unsigned char *program = read_file(argv[1], &len);
    if (!program) {
        perror(argv[1]);
        return 1;
    }

    GbcMachine machine = 0;
    GbcStatus s;
    if (argc == 3) {
        size_t tlen = 0;
        unsigned char *text = read_file(argv[2], &tlen);
        if (!text) {
            perror(argv[2]);
            free(program);
            return 1;
        }
        s = gbc_machine_from_toml((const char *)text, tlen, &machine);
        free(text);
    } else {
        s = gbc_machine_reference(&machine);
    }
    if (s != GBC_STATUS_OK) {
        free(program);
        return fail("machine", s);
    }

    static struct host host; /* zeroed, then all vacant */
    for (size_t i = 0; i < GBC_PERSISTENT_COUNT; i++)
        host.vars[i] = NAN;
    GbcHost callbacks = {
        .user = &host,
        .plc_request = plc_request,
        .plc_done = plc_done,
        .vars_load = vars_load,
        .vars_store = vars_store,
    };
    GbcController ctl = 0;
    s = gbc_controller_new(machine, &callbacks, &ctl);
    gbc_machine_free(machine); /* the controller keeps its own copy */
    if (s != GBC_STATUS_OK) {
        free(program);
        return fail("controller", s);
    }
    /* G-code text (.nc) is compiled by the library for the machine. */
    size_t name_len = strlen(argv[1]);
    if (name_len > 3 && strcmp(argv[1] + name_len - 3, ".nc") == 0)
        s = gbc_controller_load_source(ctl, argv[1], (const char *)program, len);
    else
        s = gbc_controller_load(ctl, program, len);
    free(program);
    if (s != GBC_STATUS_OK) {
        gbc_controller_free(ctl);
        return fail("load", s);
    }

    int status = 0, header = 0;
    gbc_cycle_start(ctl);
    for (;;) {
        /* Ordinary context: keep the planner fed. */
        if ((s = gbc_run_ahead(ctl)) != GBC_STATUS_OK) {
            status = fail("run ahead", s);
            break;
        }
        /* Real-time context: one period. */
        GbcSetPoint sp;
        if ((s = gbc_tick(ctl, &sp)) != GBC_STATUS_OK) {
            status = fail("tick", s);
            break;
        }
        report_room(ctl);
        if (!header) {
            header = 1;
            printf(sp.has_c ? "time_s,x,z,c,spindle_rpm,feed,line,motion,tool,file\n"
                            : "time_s,x,z,spindle_rpm,feed,line,motion,tool,file\n");
        }
        put_fixed(sp.time_s, 6);
        putchar(',');
        put_fixed(sp.x, 6);
        putchar(',');
        put_fixed(sp.z, 6);
        putchar(',');
        if (sp.has_c) {
            put_fixed(sp.c, 6);
            putchar(',');
        }
        put_fixed(sp.spindle_rpm, 3);
        putchar(',');
        put_fixed(sp.feed, 3);
        printf(",%u,%s,%u,", sp.line, motion_word(sp.motion), sp.tool);
        char file[256];
        size_t file_len = 0;
        if ((s = gbc_file_name(ctl, sp.file, file, sizeof file, &file_len)) != GBC_STATUS_OK) {
            status = fail("file name", s);
            break;
        }
        if (file_len < sizeof file) {
            put_csv_field(file);
        } else {
            /* Cut: ask again with room for the whole name. */
            char *whole = malloc(file_len + 1);
            if (!whole) {
                fprintf(stderr, "controller: out of memory\n");
                status = 1;
                break;
            }
            s = gbc_file_name(ctl, sp.file, whole, file_len + 1, NULL);
            if (s == GBC_STATUS_OK)
                put_csv_field(whole);
            free(whole);
            if (s != GBC_STATUS_OK) {
                status = fail("file name", s);
                break;
            }
        }
        putchar('\n');

        GbcStateInfo st;
        if ((s = gbc_state(ctl, &st)) != GBC_STATUS_OK) {
            status = fail("state", s);
            break;
        }
        if (st.state == GBC_RUN_STATE_STOPPED || st.state == GBC_RUN_STATE_IDLE) {
            gbc_cycle_start(ctl);
        } else if (st.state == GBC_RUN_STATE_ENDED) {
            break;
        } else if (st.state == GBC_RUN_STATE_ALARM) {
            GbcAlarm a;
            if (gbc_alarm(ctl, &a) == GBC_STATUS_OK)
                fprintf(stderr, "%s:%u:%u: alarm %u: %s\n", (const char *)a.file, a.line,
                        a.column, a.code, (const char *)a.message);
            status = 2;
            break;
        }
    }
    fprintf(stderr, "controller: %u PLC functions, %u stores of #500-#999\n",
            host.plc_functions, host.stores);
    print_active(ctl);
    gbc_controller_free(ctl);
    return status;
}
