/* semihosting.h: text out and exit through ARM semihosting (startup.c). */
#ifndef RFISST_SEMIHOSTING_H
#define RFISST_SEMIHOSTING_H

/* Writes a NUL-terminated text to the host's console. */
void sh_puts(const char *text);
/* Ends the QEMU run with `status`. */
void sh_exit(int status) __attribute__((noreturn));

#endif
