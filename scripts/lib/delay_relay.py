"""A TCP relay that delays each direction: what scripts/bench-remote-haptics uses where the
kernel has no tc netem (sch_netem).

    delay_relay.py LISTEN_PORT TARGET_HOST TARGET_PORT ONE_WAY_MS JITTER_MS LOSS_PERCENT

Listens on 127.0.0.1:LISTEN_PORT and relays each connection to TARGET, holding every chunk read
for ONE_WAY_MS plus normally distributed jitter (standard deviation JITTER_MS / 2, as the script
gives netem), in order: a chunk never overtakes the one before, as TCP delivers. Loss is TCP's:
a lost segment comes after a retransmission timeout (Linux's least, 200 ms) and holds back
everything behind it. Prints "relaying" once listening.
"""

import asyncio
import random
import sys
import time

RETRANSMISSION_S = 0.2


async def pipe(reader, writer, one_way, jitter, loss):
    queue = asyncio.Queue()
    last_due = 0.0

    async def send():
        while True:
            due, data = await queue.get()
            if data is None:
                writer.close()
                return
            wait = due - time.monotonic()
            if wait > 0:
                await asyncio.sleep(wait)
            writer.write(data)
            await writer.drain()

    sender = asyncio.ensure_future(send())
    while True:
        data = await reader.read(65536)
        delay = max(0.0, one_way + random.gauss(0, jitter / 2)) if jitter > 0 else one_way
        if random.random() < loss:
            delay += RETRANSMISSION_S
        last_due = max(last_due, time.monotonic() + delay)
        await queue.put((last_due, data or None))
        if not data:
            break
    await sender


async def main():
    port, host, target_port = int(sys.argv[1]), sys.argv[2], int(sys.argv[3])
    one_way, jitter, loss = float(sys.argv[4]) / 1000, float(sys.argv[5]) / 1000, \
        float(sys.argv[6]) / 100

    async def relay(client_reader, client_writer):
        server_reader, server_writer = await asyncio.open_connection(host, target_port)
        for w in (client_writer, server_writer):
            sock = w.get_extra_info("socket")
            sock.setsockopt(6, 1, 1)  # TCP_NODELAY
        await asyncio.gather(pipe(client_reader, server_writer, one_way, jitter, loss),
                             pipe(server_reader, client_writer, one_way, jitter, loss))

    server = await asyncio.start_server(relay, "127.0.0.1", port)
    print("relaying", flush=True)
    async with server:
        await server.serve_forever()


if __name__ == "__main__":
    asyncio.run(main())
