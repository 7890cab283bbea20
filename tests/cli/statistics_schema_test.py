#!/usr/bin/env python3
"""The statistics JSON that `membrane reconstruct` writes (the same text a server sends in
ResultHeader.statistics_json) conforms to proto/membrane/v1/statistics.schema.json, which
forbids keys it does not describe: the schema clients read and the code cannot drift apart.

Usage: statistics_schema_test.py SOURCE_DIR MEMBRANE_BINARY
"""
import json
import subprocess
import sys
import tempfile

import jsonschema


def stats_of(membrane, scratch, shape, extra):
    cloud = f"{scratch}/{shape}.ply"
    subprocess.run([membrane, "synth", shape, "-o", cloud, "--points", "20000"], check=True,
                   stdout=subprocess.DEVNULL)
    stats = f"{scratch}/{shape}.json"
    subprocess.run([membrane, "reconstruct", cloud, "-o", f"{scratch}/{shape}.drc", "--local",
                    "-q", "--stats-json", stats] + extra, check=True, stdout=subprocess.DEVNULL)
    with open(stats) as f:
        return json.load(f)


def main():
    source_dir, membrane = sys.argv[1], sys.argv[2]
    with open(f"{source_dir}/proto/membrane/v1/statistics.schema.json") as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    failures = 0
    with tempfile.TemporaryDirectory() as scratch:
        for shape, extra in [("torus", []), ("two-spheres", ["--no-relax", "--surface", "cuberille"]),
                             ("sphere", ["--target-faces", "1000"])]:
            stats = stats_of(membrane, scratch, shape, extra)
            for error in validator.iter_errors(stats):
                failures += 1
                print(f"{shape}: {'/'.join(map(str, error.absolute_path))}: {error.message}")
            # The schema's stage names are the keys the stream's StageEvents use.
            if set(stats["seconds"]) != set(schema["properties"]["seconds"]["properties"]):
                failures += 1
                print(f"{shape}: seconds keys {sorted(stats['seconds'])}")
        # A key the code does not write would make the schema lie: every required key exists.
        bogus = dict(stats, unknown_key=1)
        if validator.is_valid(bogus):
            failures += 1
            print("the schema accepts keys it does not describe")
    if failures:
        print(f"FAILED: {failures} problems")
        return 1
    print("statistics JSON conforms to proto/membrane/v1/statistics.schema.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
