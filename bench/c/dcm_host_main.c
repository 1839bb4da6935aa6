/*
 * dcm_host_main.c - the estimator benchmark's flight on the host: prints the
 * final ht_dcm_state_t as hex bytes, which bench_dcm.py compares with the
 * Cortex-M0 and M4 runs (the portable and the SMULL products must agree).
 * Usage: dcm_host <samples>
 */
#include <stdio.h>
#include <stdlib.h>

#include "helical/estimator/dcm.h"

extern ht_dcm_state_t dcm_bench_s;
int dcm_bench_setup(void);
void dcm_bench_prepare(uint32_t k);
void dcm_bench_update(void);
void dcm_bench_output(void);

int main(int argc, char **argv)
{
    const unsigned long n = (argc > 1) ? strtoul(argv[1], NULL, 10) : 0ul;
    if (dcm_bench_setup() != 0) {
        return 1;
    }
    for (unsigned long k = 0; k < n; k++) {
        dcm_bench_prepare((uint32_t)k);
        dcm_bench_update();
        if (k % 5u == 0u) {
            dcm_bench_output();
        }
    }
    const unsigned char *b = (const unsigned char *)&dcm_bench_s;
    for (size_t i = 0; i < sizeof dcm_bench_s; i++) {
        printf("%02x", b[i]);
    }
    printf("\n");
    return 0;
}
