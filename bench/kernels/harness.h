/* Runs cycle() CYCLES times (argv[1], default 1000) and prints the
   nanoseconds per cycle of the fastest of 20 repetitions, in CPU time of
   the process (the benchmark machine is shared). cycle() is called
   through a pointer, as a runtime's task table calls a program (and as the
   timing main of generated C calls its body): inlined into the timing loop,
   gcc would hoist work out of it across cycles, which no scan does. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
static double now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}
int main(int argc, char **argv) {
    long cycles = argc > 1 ? atol(argv[1]) : 1000;
    double best = 1e300;
    void (*volatile run)(void) = cycle;
    for (int rep = 0; rep < 20; rep++) {
        double t0 = now_ns();
        for (long k = 0; k < cycles; k++) run();
        double dt = (now_ns() - t0) / (double)cycles;
        if (dt < best) best = dt;
    }
    printf("%.1f\n", best);
    return 0;
}
