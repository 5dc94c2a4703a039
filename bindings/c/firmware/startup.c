/* startup.c: the bare-metal start of the C firmware on QEMU's mps2-an386 (Cortex-M4F): the vector table,
 * the reset handler (FPU on, .bss zeroed, main, exit), fault handlers, and ARM semihosting (text out and
 * exit) so that the firmware needs no C library. */
#include "semihosting.h"

#include <stdint.h>

extern uint32_t __bss_start, __bss_end, __stack_top;
int main(void);

/* ARM semihosting: operation `op` with parameter block `arg`, through BKPT 0xAB. */
static int semihost(int op, const void *arg) {
    register int r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

/* The host's standard output: SYS_OPEN of ":tt" for writing (QEMU sends SYS_WRITE0 to stderr). */
static int console = -1;

void sh_puts(const char *text) {
    if (console < 0) {
        const uint32_t open[3] = {(uint32_t)":tt", 4 /* "w" */, 3 /* strlen(":tt") */};
        console = semihost(0x01 /* SYS_OPEN */, open);
    }
    uint32_t length = 0;
    while (text[length]) length++;
    const uint32_t write[3] = {(uint32_t)console, (uint32_t)text, length};
    semihost(0x05 /* SYS_WRITE */, write);
}

void sh_exit(int status) {
    /* SYS_EXIT_EXTENDED: reason ADP_Stopped_ApplicationExit and the exit code. */
    const uint32_t block[2] = {0x20026, (uint32_t)status};
    semihost(0x20, block);
    for (;;) __asm__ volatile("wfi");
}

void reset_handler(void) {
    /* Full access to coprocessors 10 and 11 (the FPU) before any floating-point instruction. */
    volatile uint32_t *cpacr = (volatile uint32_t *)0xE000ED88u;
    *cpacr |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    for (uint32_t *word = &__bss_start; word < &__bss_end; word++) *word = 0;
    sh_exit(main());
}

static void fault_handler(void) {
    sh_puts("c-firmware: fault\n");
    sh_exit(1);
}

/* Initial stack pointer, reset, then NMI, HardFault, MemManage, BusFault, UsageFault. */
__attribute__((section(".vectors"), used)) static void (*const vectors[8])(void) = {
    (void (*)(void))(&__stack_top), reset_handler, fault_handler, fault_handler,
    fault_handler,                  fault_handler, fault_handler, 0,
};
