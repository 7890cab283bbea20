#!/usr/bin/env python3
"""A membrane client in Python that needs only grpcio and protobuf (Debian: python3-grpcio,
python3-protobuf) and protoc: it uploads a Draco point cloud to membraned, follows its job,
and writes the mesh as binary PLY, which Python reads without a Draco decoder.

    python3 client/python/membrane_client.py CLOUD.drc -o MESH.ply --server 127.0.0.1:50051

The message classes are generated from proto/ at start-up with protoc into a temporary
directory; the calls use grpcio's generic stubs, so no gRPC code generator is needed.
Exit status as `membrane`'s: 0 success, 2 usage, 3 invalid input, 4 server unavailable or
busy, 5 job failed or cancelled; errors are one line "membrane_client: <message>" on stderr.
"""
import argparse
import importlib
import os
import subprocess
import sys
import tempfile

import grpc

CHUNK_BYTES = 1 << 20  # the proto's bound on an upload chunk
EXIT_INVALID, EXIT_UNAVAILABLE, EXIT_FAILED = 3, 4, 5


def _crc32c_table():
    table = []
    for byte in range(256):
        crc = byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0x82F63B78 if crc & 1 else crc >> 1
        table.append(crc)
    return table


_CRC_TABLE = _crc32c_table()


def crc32c(data: bytes) -> int:
    """CRC-32C (Castagnoli) of `data`, as proto/crc32c.h computes it."""
    crc = 0xFFFFFFFF
    table = _CRC_TABLE
    for byte in data:
        crc = table[(crc ^ byte) & 0xFF] ^ (crc >> 8)
    return crc ^ 0xFFFFFFFF


def load_messages(proto_dir: str):
    """The module of membrane/v1/reconstruction.proto's messages, generated with protoc."""
    out = tempfile.mkdtemp(prefix="membrane_client_")
    subprocess.run(["protoc", f"--proto_path={proto_dir}", f"--python_out={out}",
                    "membrane/v1/reconstruction.proto", "google/rpc/status.proto"],
                   check=True)
    sys.path.insert(0, out)
    return importlib.import_module("membrane.v1.reconstruction_pb2")


class JobFailed(Exception):
    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


def reconstruct(channel, pb, cloud: bytes, token=None, progress=sys.stderr, **parameters):
    """Uploads `cloud` (Draco bytes), follows the job, and returns (statistics JSON, mesh
    bytes as PLY). Raises grpc.RpcError when the call fails before a job exists, JobFailed
    when the job ends FAILED or CANCELLED, ValueError when the mesh arrives damaged."""
    call = channel.stream_stream(
        "/membrane.v1.Reconstruction/Reconstruct",
        request_serializer=pb.ReconstructRequest.SerializeToString,
        response_deserializer=pb.JobEvent.FromString)
    header = pb.ReconstructRequest()
    header.header.parameters.mesh_format = pb.MESH_FORMAT_PLY
    for key, value in parameters.items():
        setattr(header.header.parameters, key, value)
    header.header.upload_bytes = len(cloud)
    header.header.upload_crc32c = crc32c(cloud)

    def requests():
        yield header
        for start in range(0, len(cloud), CHUNK_BYTES):
            yield pb.ReconstructRequest(chunk=cloud[start:start + CHUNK_BYTES])

    metadata = [("authorization", f"Bearer {token}")] if token else None
    statistics, result, chunks, done = "", None, [], None
    for event in call(requests(), metadata=metadata):
        kind = event.WhichOneof("event")
        if kind == "accepted":
            print(f"job {event.accepted.job_id} accepted, queue position "
                  f"{event.accepted.queue_position}", file=progress)
        elif kind == "stage" and event.stage.phase == pb.StageEvent.FINISHED:
            print(event.stage.line, file=progress)
        elif kind == "result":
            result = event.result
            statistics = result.statistics_json
        elif kind == "mesh_chunk":
            chunks.append(event.mesh_chunk)
        elif kind == "done":
            done = event.done
    if done is None or done.state != pb.SUCCEEDED:
        # The stream of a failed job ends with a non-OK status, raised by the loop above.
        raise JobFailed(done.status.code if done else 2, "the job ended without its result")
    mesh = b"".join(chunks)
    if result is None or len(mesh) != result.mesh_bytes or crc32c(mesh) != result.mesh_crc32c:
        raise ValueError("the mesh arrived damaged (size or CRC-32C differ from the header)")
    return statistics, mesh


def main(argv):
    parser = argparse.ArgumentParser(prog="membrane_client", description=__doc__.split("\n\n")[0])
    parser.add_argument("cloud", help="Draco point cloud to upload (.drc)")
    parser.add_argument("-o", "--output", required=True, help="mesh to write (binary PLY)")
    parser.add_argument("--server", default="127.0.0.1:50051", help="HOST:PORT of membraned")
    parser.add_argument("--token-file", help="file whose first line is the bearer token")
    parser.add_argument("--stats-json", help="write the statistics JSON here")
    parser.add_argument("--voxel-size", type=float, default=0.0, help="0 = the server's formula")
    parser.add_argument("--proto-dir", default=os.path.join(os.path.dirname(__file__), "..",
                                                            "..", "proto"),
                        help="the repository's proto/ folder")
    args = parser.parse_args(argv)

    def fail(code, message):
        print(f"membrane_client: {message}", file=sys.stderr)
        return code

    try:
        with open(args.cloud, "rb") as f:
            cloud = f.read()
        token = None
        if args.token_file:
            with open(args.token_file) as f:
                token = f.readline().strip()
    except OSError as e:
        return fail(EXIT_INVALID, f"{e.filename}: {e.strerror}")
    pb = load_messages(args.proto_dir)
    with grpc.insecure_channel(args.server) as channel:
        try:
            statistics, mesh = reconstruct(channel, pb, cloud, token,
                                           voxel_size=args.voxel_size)
        except grpc.RpcError as e:
            code = e.code()
            exit_code = (EXIT_UNAVAILABLE if code in (grpc.StatusCode.UNAVAILABLE,
                                                      grpc.StatusCode.RESOURCE_EXHAUSTED,
                                                      grpc.StatusCode.DEADLINE_EXCEEDED)
                         else EXIT_INVALID if code in (grpc.StatusCode.INVALID_ARGUMENT,
                                                       grpc.StatusCode.UNAUTHENTICATED)
                         else EXIT_FAILED)
            return fail(exit_code, f"server {args.server}: {code.name}: {e.details()}")
        except (JobFailed, ValueError) as e:
            return fail(EXIT_FAILED, str(e))
    try:
        with open(args.output, "wb") as f:
            f.write(mesh)
        if args.stats_json:
            with open(args.stats_json, "w") as f:
                f.write(statistics)
    except OSError as e:
        return fail(EXIT_INVALID, f"{e.filename}: {e.strerror}")
    print(f"wrote {len(mesh)} bytes of PLY to {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
