/*
 * fw.h -- semihosting for the suite firmware (ARM semihosting interface:
 * BKPT 0xAB with the operation in r0 and its argument in r1).
 */
#ifndef CAROM_EMBEDDED_FW_H
#define CAROM_EMBEDDED_FW_H

/* Write a NUL-terminated string to the debugger's console (SYS_WRITE0). */
void fw_write(const char *s);
/* Stop with status 0 (ADP_Stopped_ApplicationExit) or 1 (SYS_EXIT). */
void fw_exit(int status) __attribute__((noreturn));

#endif
