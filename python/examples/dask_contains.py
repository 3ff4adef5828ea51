#!/usr/bin/env python3
"""Classify 100 million points against a real model with Dask.

    python3 python/examples/dask_contains.py MODEL.obj [--points 100e6] [--chunk 2e6] [--workers 2]

The pattern a user with billions of points follows on a cluster: the pickled
``wingedge.Solid`` is sent once to every worker (``client.scatter(...,
broadcast=True)``), each task makes (or would read) one chunk of points where
it runs and maps ``contains`` over it, and only the counts travel back. Each
worker process runs single-threaded queries (``RAYON_NUM_THREADS=1``), so the
cluster's parallelism is its processes.

Prints the single-process rate (all cores, one call per chunk) beside the
cluster's, and checks that both count the same points inside.
"""

import argparse
import os
import time

import numpy as np

import wingedge


def chunk_points(lo, hi, seed, n):
    """The seeded points of one chunk, uniform in the box [lo, hi]."""
    rng = np.random.default_rng(seed)
    return rng.uniform(lo, hi, size=(n, 3))


def count_inside(solid, lo, hi, seed, n):
    """How many of one chunk's points the solid contains."""
    return int(solid.contains(chunk_points(lo, hi, seed, n)).sum())


def chunks(total, size):
    out, start = [], 0
    while start < total:
        out.append(min(size, total - start))
        start += size
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model")
    parser.add_argument("--points", type=float, default=100e6)
    parser.add_argument("--chunk", type=float, default=2e6)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument(
        "--single-points",
        type=float,
        default=20e6,
        help="points for the single-process rate (a prefix of the same chunks)",
    )
    args = parser.parse_args()

    solid = wingedge.load_obj(args.model)
    lo, hi = solid.bounds
    sizes = chunks(int(args.points), int(args.chunk))
    print(f"model {args.model}: {solid.face_count} faces; {int(args.points):,} points in {len(sizes)} chunks")

    # One process, every core: the rate to beat.
    single = sizes[: max(1, int(args.single_points // args.chunk))]
    t0 = time.perf_counter()
    inside_single = sum(count_inside(solid, lo, hi, seed, n) for seed, n in enumerate(single))
    single_s = time.perf_counter() - t0
    single_rate = sum(single) / single_s

    # Workers are processes with one query thread each.
    os.environ["RAYON_NUM_THREADS"] = "1"
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True) as cluster, Client(
        cluster
    ) as client:
        shared = client.scatter(solid, broadcast=True)
        client.submit(count_inside, shared, lo, hi, 0, 10).result()  # warm the workers
        t0 = time.perf_counter()
        futures = [client.submit(count_inside, shared, lo, hi, seed, n, pure=False) for seed, n in enumerate(sizes)]
        counts = client.gather(futures)
        cluster_s = time.perf_counter() - t0
    cluster_rate = sum(sizes) / cluster_s
    if sum(counts[: len(single)]) != inside_single:
        raise SystemExit("the cluster and the single process disagree on the same chunks")

    print()
    print("| run | points | seconds | million points/s | inside |")
    print("|---|---:|---:|---:|---:|")
    print(f"| one process, all cores | {sum(single):,} | {single_s:.2f} | {single_rate / 1e6:.1f} | {inside_single:,} |")
    print(
        f"| Dask LocalCluster, {args.workers} workers | {sum(sizes):,} | {cluster_s:.2f} | "
        f"{cluster_rate / 1e6:.1f} | {sum(counts):,} |"
    )
    print(f"\ncluster rate / single-process rate: {cluster_rate / single_rate:.2f}")


if __name__ == "__main__":
    main()
