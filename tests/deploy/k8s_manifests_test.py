#!/usr/bin/python3
"""The Kubernetes manifests (deploy/k8s) and compose file, checked without a cluster.

- Schema: every field of every document is one the Kubernetes API defines, with the right
  type, as the models of Debian's python3-kubernetes give them (22.6: the 1.22 API; the few
  newer fields we use are listed in NEWER_FIELDS with their Kubernetes version).
- Cross-references: selectors and labels, Service ports and container port names, the
  StatefulSet's serviceName, the HPA's and the PDBs' targets, volume names, the names nginx.conf
  sends calls to, the image's user.
- Hardening: non-root numeric users, read-only roots, no privilege escalation, no
  capabilities, RuntimeDefault seccomp, an imagePullPolicy, a startupProbe for membraned.
- The programs: membraned started with the StatefulSet's and compose's own arguments
  (addresses and paths moved here), answering the health check the probes make; exec
  health checks whose --timeout is below their own timeout.

Usage: k8s_manifests_test.py SOURCE_DIR MEMBRANED MEMBRANE
"""

import os
import re
import select
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import yaml

try:
    import kubernetes.client as k8s
    from kubernetes.client.api_client import ApiClient
except ImportError:  # a clear failure, not a skip: deploy/install-deps.sh test installs it
    sys.exit("python3-kubernetes is missing (deploy/install-deps.sh test installs it)")

SOURCE, MEMBRANED, MEMBRANE = sys.argv[1:4] if len(sys.argv) >= 4 else (None, None, None)

# The model class of each kind we ship. autoscaling/v2 (Kubernetes 1.23) has the schema of
# v2beta2, which the 1.22 models have.
MODELS = {
    ("apps/v1", "StatefulSet"): "V1StatefulSet",
    ("apps/v1", "Deployment"): "V1Deployment",
    ("v1", "Service"): "V1Service",
    ("policy/v1", "PodDisruptionBudget"): "V1PodDisruptionBudget",
    ("autoscaling/v2", "HorizontalPodAutoscaler"): "V2beta2HorizontalPodAutoscaler",
}
# Fields newer than the packaged models: model -> {field: type}.
NEWER_FIELDS = {
    "V1Probe": {"grpc": "GRPCAction"},  # gRPC probes: beta 1.24 (on by default), GA 1.27
}
# Their own types: field -> (type, required).
NEWER_TYPES = {"GRPCAction": {"port": ("int", True), "service": ("str", False)}}


def schema_errors(value, type_name, path):
    """Every field of `value` not in `type_name`'s schema, or of the wrong type."""
    errors = []
    if type_name == "object":
        return errors
    if type_name.startswith("list["):
        if not isinstance(value, list):
            return [f"{path}: expected a list"]
        for i, item in enumerate(value):
            errors += schema_errors(item, type_name[5:-1], f"{path}[{i}]")
        return errors
    if type_name.startswith("dict("):
        if not isinstance(value, dict):
            return [f"{path}: expected a mapping"]
        inner = type_name[5:-1].split(", ", 1)[1]
        quantity = path.endswith((".limits", ".requests"))  # Kubernetes quantities: 4 or "4"
        for key, item in value.items():
            if quantity and isinstance(item, (int, float)) and not isinstance(item, bool):
                continue
            errors += schema_errors(item, inner, f"{path}.{key}")
        return errors
    primitive = {"str": str, "int": int, "bool": bool, "float": (int, float)}.get(type_name)
    if primitive is not None:
        if not isinstance(value, primitive) or (type_name == "int" and isinstance(value, bool)):
            return [f"{path}: expected {type_name}, got {value!r}"]
        return errors
    if not isinstance(value, dict):
        return [f"{path}: expected a {type_name} mapping"]
    if type_name in NEWER_TYPES:
        fields = NEWER_TYPES[type_name]
        for key, item in value.items():
            if key not in fields:
                errors.append(f"{path}.{key}: no such field of {type_name}")
            else:
                errors += schema_errors(item, fields[key][0], f"{path}.{key}")
        errors += [f"{path}.{k}: required" for k, (_, req) in fields.items()
                   if req and k not in value]
        return errors
    model = getattr(k8s, type_name)
    by_json = {json: attr for attr, json in model.attribute_map.items()}
    newer = NEWER_FIELDS.get(type_name, {})
    for key, item in value.items():
        if key in newer:
            errors += schema_errors(item, newer[key], f"{path}.{key}")
        elif key not in by_json:
            errors.append(f"{path}.{key}: no such field of {type_name}")
        else:
            errors += schema_errors(item, model.openapi_types[by_json[key]], f"{path}.{key}")
    return errors


def read_text(*parts):
    with open(os.path.join(*parts)) as f:
        return f.read()


def load_documents(path):
    with open(path) as f:
        return [d for d in yaml.safe_load_all(f) if d is not None]


def pod_spec(doc):
    return doc["spec"]["template"]["spec"]


def flag_value(args, name):
    """The value of --name=VALUE in args, or None."""
    for arg in args:
        if arg.startswith(f"--{name}="):
            return arg.split("=", 1)[1]
    return None


def exec_timeout(command):
    """The --timeout of a `membrane health` command, seconds (its default: 5)."""
    if "--timeout" in command:
        return float(command[command.index("--timeout") + 1])
    return 5.0


def dockerfile_user(path):
    users = re.findall(r"^USER\s+(\S+)", read_text(path), re.M)
    return users[-1] if users else None


class Manifests(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.k8s_dir = os.path.join(SOURCE, "deploy", "k8s")
        cls.docs = []
        for name in sorted(os.listdir(cls.k8s_dir)):
            if name.endswith(".yaml"):
                for doc in load_documents(os.path.join(cls.k8s_dir, name)):
                    cls.docs.append((name, doc))
        cls.by_kind = {}
        for name, doc in cls.docs:
            cls.by_kind.setdefault(doc["kind"], {})[doc["metadata"]["name"]] = doc
        cls.statefulset = cls.by_kind["StatefulSet"]["membraned"]
        cls.balancer = cls.by_kind["Deployment"]["membrane-balancer"]
        cls.workloads = [cls.statefulset, cls.balancer]
        cls.nginx_conf = read_text(SOURCE, "deploy", "nginx", "nginx.conf")

    def test_every_document_matches_the_schema(self):
        self.assertGreaterEqual(len(self.docs), 7)
        api = ApiClient()
        for name, doc in self.docs:
            key = (doc.get("apiVersion"), doc.get("kind"))
            self.assertIn(key, MODELS, f"{name}: no model for {key}")
            where = f"{name}:{doc['kind']}/{doc['metadata']['name']}"
            errors = schema_errors(doc, MODELS[key], where)
            self.assertEqual(errors, [], "\n".join(errors))
            # The models' constructors check required fields.
            api._ApiClient__deserialize(doc, MODELS[key])

    def test_the_schema_check_finds_a_misspelt_field(self):
        doc = yaml.safe_load(yaml.safe_dump(self.statefulset))
        container = pod_spec(doc)["containers"][0]
        container["securityContext"]["readOnlyRootFileSystem"] = True
        container["readinessProbe"]["grpc"]["timeout"] = 3
        errors = sorted(schema_errors(doc, "V1StatefulSet", "s"))
        self.assertEqual(len(errors), 2, errors)
        self.assertIn("grpc.timeout: no such field of GRPCAction", errors[0])
        self.assertIn("readOnlyRootFileSystem: no such field of V1SecurityContext", errors[1])

    def test_selectors_match_the_pods(self):
        for w in self.workloads:
            labels = w["spec"]["template"]["metadata"]["labels"]
            for k, v in w["spec"]["selector"]["matchLabels"].items():
                self.assertEqual(labels.get(k), v, w["metadata"]["name"])

        def pods_of(selector):
            return [w for w in self.workloads
                    if all(w["spec"]["template"]["metadata"]["labels"].get(k) == v
                           for k, v in selector.items())]

        for svc in self.by_kind["Service"].values():
            pods = pods_of(svc["spec"]["selector"])
            self.assertEqual(len(pods), 1, f"Service {svc['metadata']['name']} selects {pods}")
            names = {p["name"]: p["containerPort"]
                     for c in pod_spec(pods[0])["containers"] for p in c.get("ports", [])}
            for port in svc["spec"]["ports"]:
                target = port["targetPort"]
                self.assertIn(target, names, f"Service {svc['metadata']['name']}: {target}")
        for pdb in self.by_kind["PodDisruptionBudget"].values():
            self.assertEqual(len(pods_of(pdb["spec"]["selector"]["matchLabels"])), 1,
                             pdb["metadata"]["name"])
        self.assertEqual(set(self.by_kind["PodDisruptionBudget"]),
                         {"membraned", "membrane-balancer"})

    def test_the_statefulset_has_its_services_and_scaler(self):
        pods = self.by_kind["Service"][self.statefulset["spec"]["serviceName"]]
        self.assertEqual(pods["spec"]["clusterIP"], "None")
        self.assertTrue(pods["spec"]["publishNotReadyAddresses"])
        target = self.by_kind["HorizontalPodAutoscaler"]["membraned"]["spec"]["scaleTargetRef"]
        self.assertEqual((target["kind"], target["name"]), ("StatefulSet", "membraned"))

    def test_volume_mounts_name_volumes(self):
        for w in self.workloads:
            names = {v["name"] for v in pod_spec(w).get("volumes", [])}
            names |= {t["metadata"]["name"] for t in w["spec"].get("volumeClaimTemplates", [])}
            for c in pod_spec(w)["containers"]:
                for m in c.get("volumeMounts", []):
                    self.assertIn(m["name"], names, f"{w['metadata']['name']}: {m}")

    def test_nginx_sends_calls_to_the_services(self):
        port = self.by_kind["Service"]["membraned"]["spec"]["ports"][0]["port"]
        self.assertIn(f'"membraned.default.svc.cluster.local:{port}"', self.nginx_conf)
        self.assertIn(f'"${{replica}}.{self.statefulset["spec"]["serviceName"]}'
                      f'.default.svc.cluster.local:{port}"', self.nginx_conf)
        # The header names pods of the StatefulSet: NAME-ORDINAL.
        self.assertIn(f'{self.statefulset["metadata"]["name"]}-[0-9]{{1,4}}', self.nginx_conf)
        listen = int(re.search(r"listen (\d+) http2;", self.nginx_conf).group(1))
        ports = [p["containerPort"] for p in pod_spec(self.balancer)["containers"][0]["ports"]]
        self.assertEqual(ports, [listen])

    def test_pods_run_hardened(self):
        images = {"membrane:": "deploy/Dockerfile", "membrane-balancer:": "deploy/nginx/Dockerfile"}
        for w in self.workloads:
            name = w["metadata"]["name"]
            pod = pod_spec(w)["securityContext"]
            self.assertTrue(pod["runAsNonRoot"], name)
            self.assertIsInstance(pod["runAsUser"], int, name)
            self.assertNotEqual(pod["runAsUser"], 0, name)
            self.assertEqual(pod["seccompProfile"], {"type": "RuntimeDefault"}, name)
            for c in pod_spec(w)["containers"]:
                sc = c["securityContext"]
                self.assertTrue(sc["readOnlyRootFilesystem"], name)
                self.assertFalse(sc["allowPrivilegeEscalation"], name)
                self.assertEqual(sc["capabilities"]["drop"], ["ALL"], name)
                self.assertNotIn("add", sc["capabilities"], name)
                self.assertIn(c["imagePullPolicy"], ("IfNotPresent", "Always", "Never"), name)
                # The user the image was built for, so that files it owns are writable.
                dockerfile = [f for prefix, f in images.items() if c["image"].startswith(prefix)]
                self.assertEqual(len(dockerfile), 1, c["image"])
                user = dockerfile_user(os.path.join(SOURCE, dockerfile[0]))
                self.assertEqual(user, f"{pod['runAsUser']}:{pod['runAsGroup']}", name)

    def test_the_balancer_writes_only_its_volumes(self):
        mounts = [m["mountPath"] for m in pod_spec(self.balancer)["containers"][0]["volumeMounts"]]
        pid = re.search(r"^pid (\S+);", self.nginx_conf, re.M).group(1)
        self.assertIn(os.path.dirname(pid), mounts)  # nginx -s quit (preStop) reads it
        self.assertIn("/var/lib/nginx", mounts)  # the package's temporary paths

    def test_probes(self):
        c = pod_spec(self.statefulset)["containers"][0]
        grpc_port = next(p["containerPort"] for p in c["ports"] if p["name"] == "grpc")
        for kind in ("startupProbe", "readinessProbe", "livenessProbe"):
            probe = c[kind]
            self.assertEqual(probe["grpc"]["port"], grpc_port, kind)
            self.assertNotIn("exec", probe, kind)
        # The liveness probe waits for startup: the startup probe must allow the store's load.
        startup = c["startupProbe"]
        self.assertGreaterEqual(startup["periodSeconds"] * startup["failureThreshold"], 60)
        grace = float(flag_value(c["args"], "grace-seconds"))
        self.assertGreater(pod_spec(self.statefulset)["terminationGracePeriodSeconds"], grace)
        for w in self.workloads:
            for c in pod_spec(w)["containers"]:
                for kind in ("startupProbe", "readinessProbe", "livenessProbe"):
                    if "exec" in c.get(kind, {}):
                        self.assertLess(exec_timeout(c[kind]["exec"]["command"]),
                                        c[kind].get("timeoutSeconds", 1), kind)

    def test_docker_healthchecks_time_out_after_their_command(self):
        dockerfile = read_text(SOURCE, "deploy", "Dockerfile")
        m = re.search(r"^HEALTHCHECK .*--timeout=(\d+)s CMD (\[.*\])$", dockerfile, re.M)
        self.assertIsNotNone(m)
        self.assertLess(exec_timeout(yaml.safe_load(m.group(2))), float(m.group(1)))
        compose = load_documents(os.path.join(SOURCE, "deploy", "compose.yaml"))[0]
        check = compose["services"]["membraned"]["healthcheck"]
        self.assertLess(exec_timeout(check["test"][1:]), float(check["timeout"].rstrip("s")))


class Programs(unittest.TestCase):
    """membraned accepts the arguments the manifests give it, and answers the probes."""

    def run_membraned(self, args, mounts):
        """Starts membraned with `args`, moved here: addresses to loopback port 0, paths under
        each mount point in `mounts` (container path -> local directory). Returns its port."""
        moved = []
        for arg in args:
            if arg.startswith(("--listen=", "--metrics-listen=")):
                arg = arg.split("=", 1)[0] + "=127.0.0.1:0"
            elif re.match(r"--[a-z-]+=/", arg):
                name, path = arg.split("=", 1)
                inside = [m for m in mounts if path.startswith(m + "/")]
                self.assertEqual(len(inside), 1, f"{arg}: a path on no volume")
                arg = f"{name}={mounts[inside[0]]}{path[len(inside[0]):]}"
            moved.append(arg)
        server = subprocess.Popen([MEMBRANED] + moved, stderr=subprocess.PIPE)
        self.addCleanup(server.stderr.close)
        self.addCleanup(server.wait, 30)
        self.addCleanup(server.send_signal, signal.SIGTERM)
        # Its log up to server_started (or its error, and its exit: the end of the pipe),
        # read unbuffered so that select() sees every byte not yet read.
        log = b""
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            ready, _, _ = select.select([server.stderr], [], [], deadline - time.monotonic())
            chunk = os.read(server.stderr.fileno(), 65536) if ready else b""
            if not chunk:
                break
            log += chunk
            m = re.search(rb"event=server_started .*? port=(\d+)", log)
            if m:
                # Later lines are read (and dropped) so that its writes never block.
                threading.Thread(target=server.stderr.read, daemon=True).start()
                return m.group(1).decode()
        self.fail(f"membraned {' '.join(moved)} did not start within 30 s:\n{log.decode()}")

    def health(self, port, *extra):
        return subprocess.run([MEMBRANE, "health", "--server", f"127.0.0.1:{port}", *extra],
                              capture_output=True, text=True, timeout=30)

    def test_statefulset_arguments(self):
        sts = Manifests.by_kind["StatefulSet"]["membraned"]
        spec = pod_spec(sts)
        c = spec["containers"][0]
        env = {e["name"]: "membraned-0" for e in c["env"]
               if e["valueFrom"]["fieldRef"]["fieldPath"] == "metadata.name"}
        args = [re.sub(r"\$\((\w+)\)", lambda m: env[m.group(1)], a) for a in c["args"]]
        tmp = tempfile.TemporaryDirectory()
        self.addCleanup(tmp.cleanup)
        mounts = {}
        for m in c["volumeMounts"]:
            here = os.path.join(tmp.name, m["name"])
            os.makedirs(here)
            mounts[m["mountPath"]] = here
        # The token Secret's key is the file membraned reads.
        secret = next(v["secret"] for v in spec["volumes"] if v["name"] == "token")
        self.assertEqual(secret["secretName"], "membrane-token")
        token_path = flag_value(args, "token-file")
        token_mount = next(m for m in c["volumeMounts"] if m["name"] == "token")["mountPath"]
        self.assertEqual(token_path, f"{token_mount}/token")  # README: --from-literal=token=
        with open(os.path.join(mounts[token_mount], "token"), "w") as f:
            f.write("secret-token\n")
        port = self.run_membraned(args, mounts)
        # What the kubelet's gRPC probe asks: the server's overall health, no token.
        result = self.health(port, "--timeout", "2")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(os.path.isdir(os.path.join(mounts["/var/lib/membrane"], "jobs")))

    def test_compose_arguments(self):
        compose = load_documents(os.path.join(SOURCE, "deploy", "compose.yaml"))[0]
        service = compose["services"]["membraned"]
        tmp = tempfile.TemporaryDirectory()
        self.addCleanup(tmp.cleanup)
        mounts = {v.split(":")[1].split()[0]: tmp.name for v in service["volumes"]}
        self.assertTrue(service["read_only"])
        self.assertEqual(service["cap_drop"], ["ALL"])
        self.assertIn("no-new-privileges:true", service["security_opt"])
        port = self.run_membraned(service["command"], mounts)
        check = service["healthcheck"]["test"]
        self.assertEqual(check[:3], ["CMD", "/usr/local/bin/membrane", "health"])
        result = self.health(port, *[a for a in check[3:] if not a.startswith("127.0.0.1:")
                                     and a != "--server"])
        self.assertEqual(result.returncode, 0, result.stderr)


if __name__ == "__main__":
    if SOURCE is None:
        sys.exit(__doc__)
    Manifests.setUpClass()
    unittest.main(argv=sys.argv[:1], verbosity=2)
