/* leptrino on a microcontroller: a gateway that keeps a sensor streaming and
 * forwards its samples, in a super-loop (see gateway.h and board.h). */
#include "board.h"
#include "gateway.h"

static gateway gw; /* the client context lives in static memory */

int main(void)
{
    board_init();
    gateway_init(&gw);
    while (!board_should_stop()) {
        gateway_poll(&gw);
        board_idle();
    }
    return 0;
}
