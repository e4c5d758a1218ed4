/* Proof that the test images really trap unaligned accesses when
 * LEPTRINO_TEST_TRAP_UNALIGNED is on: a word load from an odd address must
 * end in the fault handler (exit status 3), never print the value. */
#include <stdint.h>
#include <stdio.h>

static const uint8_t bytes[8] = { 1, 2, 3, 4, 5, 6, 7, 8 };

int main(void)
{
    /* Through a volatile integer, so the compiler cannot split the access. */
    volatile uintptr_t address = (uintptr_t)&bytes[1];
    const volatile uint32_t *word = (const volatile uint32_t *)address;
    printf("unaligned load gave 0x%08lx: no trap\n", (unsigned long)*word);
    return 0;
}
