/*
 * dspic33fj_regs.h - the dsPIC33FJ256GP710A special function registers the
 * servo driver uses: Timer2/Timer3 and Output Compare 1..8. Addresses and bit
 * positions from the device datasheet (DS70593, SFR maps "Timer register
 * map" and "Output compare register map") and the family reference manual
 * section "Output Compare" (DS70209). All SFRs are 16 bits wide.
 *
 * The driver takes pointers to these blocks, so host tests pass structs in
 * RAM; on the device (XC16) the fixed addresses below are used.
 */
#ifndef HT_DSPIC33FJ_REGS_H
#define HT_DSPIC33FJ_REGS_H

#include <stddef.h>
#include <stdint.h>

/* Timer2/Timer3 block, 0x0106..0x0113 (TMR2, TMR3HLD, TMR3, PR2, PR3,
 * T2CON, T3CON are consecutive words). */
typedef struct {
    volatile uint16_t TMR2;    /* 0x0106 */
    volatile uint16_t TMR3HLD; /* 0x0108 */
    volatile uint16_t TMR3;    /* 0x010A */
    volatile uint16_t PR2;     /* 0x010C period: the timer resets after PR2 */
    volatile uint16_t PR3;     /* 0x010E */
    volatile uint16_t T2CON;   /* 0x0110 */
    volatile uint16_t T3CON;   /* 0x0112 */
} dspic_tmr23_t;

_Static_assert((size_t)offsetof(dspic_tmr23_t, PR2) == 0x010Cu - 0x0106u, "PR2 offset");
_Static_assert((size_t)offsetof(dspic_tmr23_t, T2CON) == 0x0110u - 0x0106u, "T2CON offset");
_Static_assert((size_t)offsetof(dspic_tmr23_t, T3CON) == 0x0112u - 0x0106u, "T3CON offset");

#define DSPIC_TMR23_ADDR 0x0106u

/* TxCON */
#define DSPIC_TCON_TON         0x8000u /* bit 15: timer on */
#define DSPIC_TCON_TSIDL       0x2000u /* bit 13 */
#define DSPIC_TCON_TGATE       (1u << 6)
#define DSPIC_TCON_TCKPS_SHIFT 4u        /* TCKPS<1:0>: 00 1:1, 01 1:8, 10 1:64, 11 1:256 */
#define DSPIC_TCON_T32         (1u << 3) /* T2CON only: Timer2/3 as one 32-bit timer */
#define DSPIC_TCON_TCS         (1u << 1) /* 0 = internal clock Fcy */

/* One output-compare module: OCxRS, OCxR, OCxCON; OC1 at 0x0180, OC2 at
 * 0x0186, ... OC8 at 0x01AA (a stride of 6 bytes). */
typedef struct {
    volatile uint16_t OCRS;  /* secondary compare: the PWM duty, buffered */
    volatile uint16_t OCR;   /* compare: the duty of the current period */
    volatile uint16_t OCCON; /* control */
} dspic_oc_t;

_Static_assert(sizeof(dspic_oc_t) == 6u, "OC stride");

#define DSPIC_OC1_ADDR 0x0180u
#define DSPIC_OC_COUNT 8u

/* OCxCON */
#define DSPIC_OCCON_OCSIDL  0x2000u   /* bit 13 */
#define DSPIC_OCCON_OCFLT   (1u << 4) /* PWM fault occurred (read only) */
#define DSPIC_OCCON_OCTSEL  (1u << 3) /* 0 = Timer2, 1 = Timer3 */
#define DSPIC_OCCON_OCM_PWM 6u        /* OCM<2:0> = 110: PWM, fault pin disabled */
#define DSPIC_OCCON_OCM_OFF 0u

/* Timer1, the control tick: TMR1 0x0100, PR1 0x0102, T1CON 0x0104 (same
 * TxCON bits as above, without T32). */
typedef struct {
    volatile uint16_t TMR1;
    volatile uint16_t PR1;
    volatile uint16_t T1CON;
} dspic_tmr1_t;

#define DSPIC_TMR1_ADDR 0x0100u

/* Interrupt flag status register 0 (0x0084): T1IF is bit 3. Polled, not
 * used as an interrupt. */
#define DSPIC_IFS0_ADDR 0x0084u
#define DSPIC_IFS0_T1IF (1u << 3)

/* PORTD direction (0x02D2): OC1..OC8 are the pins RD0..RD7 of the
 * dsPIC33FJ256GP710A; 0 = output. */
#define DSPIC_TRISD_ADDR 0x02D2u

#endif /* HT_DSPIC33FJ_REGS_H */
