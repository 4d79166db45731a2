"""Bakes a stochtex model into a Zarr array with dask.distributed and reports wall time, throughput
and the peak memory of every process of the bake (client, scheduler and workers together).

Usage: /usr/bin/python3 scripts/bake_dask.py MODEL.stx OUT.zarr --size 65536 --workers 2
       [--chunk 2048] [--dtype float16]
The assembled array is the same, byte for byte, as one `model.render` of the whole size
(stochtex.dask.render); docs/python.md and docs/performance.md explain the numbers.
"""

import argparse
import os
import shutil
import threading
import time

import psutil
import stochtex
import stochtex.dask
from distributed import Client, LocalCluster


class PeakMemory:
    """Samples the summed resident memory of this process and its children every 0.2 s."""

    def __init__(self):
        self.peak = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        me = psutil.Process()
        while not self._stop.is_set():
            total = 0
            for process in [me] + me.children(recursive=True):
                try:
                    total += process.memory_info().rss
                except psutil.Error:
                    pass
            self.peak = max(self.peak, total)
            time.sleep(0.2)

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model")
    parser.add_argument("output")
    parser.add_argument("--size", type=int, default=65536, help="side of the square bake")
    parser.add_argument("--workers", type=int, default=2, help="dask worker processes")
    parser.add_argument("--chunk", type=int, default=2048, help="side of one chunk (one render)")
    parser.add_argument("--dtype", default="float16", help="stored type (float16 or float32)")
    args = parser.parse_args()

    model = stochtex.load(args.model)
    shutil.rmtree(args.output, ignore_errors=True)
    with PeakMemory() as memory:
        with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True) as cluster:
            with Client(cluster):
                start = time.perf_counter()
                array = stochtex.dask.render(model, (args.size, args.size),
                                             chunks=(args.chunk, args.chunk), seed=1)
                array.astype(args.dtype).to_zarr(args.output)
                seconds = time.perf_counter() - start
    pixels = args.size * args.size
    print(f"{args.workers} workers, {args.size}x{args.size} ({pixels / 1e9:.2f} Gpixel), "
          f"chunks {args.chunk}: {seconds:.1f} s, {pixels / seconds / 1e6:.2f} Mpixel/s, "
          f"peak memory {memory.peak / 2**20:.0f} MiB (all processes)")
    size = sum(os.path.getsize(os.path.join(d, f))
               for d, _, files in os.walk(args.output) for f in files)
    print(f"zarr store: {size / 1e9:.1f} GB")


if __name__ == "__main__":
    main()
