// Offline checks of deploy/k8s (run by tests/deploy/k8s_manifests_test.sh):
//  1. every document of every file in kustomization.yaml's resources against the Kubernetes
//     1.33 OpenAPI schema that kubernetes-models compiles with ajv (types, enums, required);
//  2. unknown fields, which those schemas let through: each object is handed to the compiled
//     validator through a Proxy that records which keys the validator reads (it reads every
//     property its schema declares); an own key it never read is not in the schema. Objects
//     whose keys the validator enumerates are maps (labels, resources) and are not checked;
//  3. what no schema says: the Deployment's selector matches its template's labels, the
//     Services and the PDB select those pods, the HPA targets the Deployment, probes and
//     targetPorts name a container port, the CPU request equals --workers, every --flag in
//     args is one `afmesh-server --help` lists, the --metrics port is a container port and the
//     prometheus.io/port annotation names it, the security context is non-root, read-only,
//     without capabilities; kustomization.yaml lists every manifest and only existing files.
// Usage: node validate.cjs MODULES_DIR K8S_DIR SERVER_BINARY [--self-test]
//   --self-test: breaks the good manifests one way at a time and requires each check to fail.
"use strict";
const fs = require("fs");
const path = require("path");
const { createRequire } = require("module");
const { execFileSync } = require("child_process");

const [modulesDir, k8sDir, serverBinary, mode] = process.argv.slice(2);
const requireModule = createRequire(path.join(path.resolve(modulesDir), "node_modules", "x.js"));
const YAML = requireModule("yaml");
const schemaDir = path.join(path.dirname(requireModule.resolve("kubernetes-models/package.json")), "_schemas");

// The kinds deploy/k8s ships; any other kind is an error, not a silent pass.
const SCHEMAS = {
  "apps/v1/Deployment": "IoK8sApiAppsV1Deployment",
  "v1/Service": "IoK8sApiCoreV1Service",
  "autoscaling/v2/HorizontalPodAutoscaler": "IoK8sApiAutoscalingV2HorizontalPodAutoscaler",
  "policy/v1/PodDisruptionBudget": "IoK8sApiPolicyV1PodDisruptionBudget",
};

function tracked(value, reads) {
  if (value === null || typeof value !== "object") return value;
  const cache = new Map();
  const info = { keys: new Set(), enumerated: false };
  reads.set(value, info);
  return new Proxy(value, {
    get(target, key) {
      if (typeof key === "string") info.keys.add(key);
      const child = target[key];
      if (child === null || typeof child !== "object") return child;
      if (!cache.has(key)) cache.set(key, tracked(child, reads));
      return cache.get(key);
    },
    has(target, key) { info.keys.add(key); return key in target; },
    getOwnPropertyDescriptor(target, key) { info.keys.add(key); return Reflect.getOwnPropertyDescriptor(target, key); },
    ownKeys(target) { info.enumerated = true; return Reflect.ownKeys(target); },
  });
}

function unknownFields(value, reads, where, out) {
  if (value === null || typeof value !== "object") return;
  if (Array.isArray(value)) { value.forEach((v, i) => unknownFields(v, reads, `${where}[${i}]`, out)); return; }
  const info = reads.get(value);
  if (info && !info.enumerated && info.keys.size > 0) {
    for (const key of Object.keys(value)) if (!info.keys.has(key)) out.push(`${where}.${key}: unknown field`);
  }
  for (const [key, child] of Object.entries(value)) unknownFields(child, reads, `${where}.${key}`, out);
}

function schemaErrors(doc, name) {
  const id = SCHEMAS[`${doc.apiVersion}/${doc.kind}`];
  if (!id) return [`${name}: no schema mapped for ${doc.apiVersion} ${doc.kind}`];
  const { validate } = requireModule(path.join(schemaDir, `${id}.js`));
  const reads = new Map();
  const errors = [];
  if (!validate(tracked(doc, reads))) {
    for (const e of validate.errors) errors.push(`${name}${e.instancePath}: ${e.keyword} ${JSON.stringify(e.params)}`);
  }
  unknownFields(doc, reads, name, errors);
  return errors;
}

const selects = (selector, labels) =>
  !!selector && Object.keys(selector).length > 0 &&
  Object.entries(selector).every(([k, v]) => labels && labels[k] === v);

function cpuCores(q) {
  const s = String(q);
  return s.endsWith("m") ? Number(s.slice(0, -1)) / 1000 : Number(s);
}

function deploymentErrors(d, serverFlags) {
  const errors = [];
  const name = `Deployment/${d.metadata?.name}`;
  const labels = d.spec?.template?.metadata?.labels;
  if (!labels || Object.keys(labels).length === 0) errors.push(`${name}: pod template has no labels`);
  if (d.spec?.selector?.matchExpressions) errors.push(`${name}: matchExpressions are not checked here; use matchLabels`);
  if (!selects(d.spec?.selector?.matchLabels, labels)) errors.push(`${name}: spec.selector does not match the template's labels`);
  const pod = d.spec?.template?.spec ?? {};
  const metricsPorts = new Set();
  if (pod.securityContext?.runAsNonRoot !== true) errors.push(`${name}: pod securityContext.runAsNonRoot is not true`);
  for (const c of pod.containers ?? []) {
    const cname = `${name} container ${c.name}`;
    const ports = new Map((c.ports ?? []).map((p) => [p.name, p.containerPort]));
    const portNumbers = new Set(ports.values());
    const sc = c.securityContext ?? {};
    if (sc.readOnlyRootFilesystem !== true) errors.push(`${cname}: readOnlyRootFilesystem is not true`);
    if (sc.allowPrivilegeEscalation !== false) errors.push(`${cname}: allowPrivilegeEscalation is not false`);
    if (!(sc.capabilities?.drop ?? []).includes("ALL")) errors.push(`${cname}: capabilities do not drop ALL`);
    for (const probe of ["readinessProbe", "livenessProbe"]) {
      const p = c[probe]?.grpc?.port;
      if (p === undefined) errors.push(`${cname}: no gRPC ${probe}`);
      else if (!portNumbers.has(p)) errors.push(`${cname}: ${probe} port ${p} is not a container port`);
    }
    for (const kind of ["requests", "limits"]) {
      for (const r of ["cpu", "memory"]) if (!c.resources?.[kind]?.[r]) errors.push(`${cname}: no resources.${kind}.${r}`);
    }
    const args = c.args ?? [];
    for (const a of args) {
      const flag = a.startsWith("--") ? a.split("=")[0] : null;
      if (flag && !serverFlags.has(flag)) errors.push(`${cname}: ${flag} is not an afmesh-server flag (--help)`);
    }
    const workers = args.find((a) => a.startsWith("--workers="));
    if (!workers) errors.push(`${cname}: no --workers= (the CPU request is sized by it)`);
    else if (cpuCores(c.resources?.requests?.cpu) !== Number(workers.split("=")[1]))
      errors.push(`${cname}: requests.cpu ${c.resources?.requests?.cpu} is not --workers (${workers})`);
    const listen = args.find((a) => a.startsWith("--listen="));
    const listenPort = listen ? Number(listen.split(":").pop()) : 50051;
    if (!portNumbers.has(listenPort)) errors.push(`${cname}: --listen port ${listenPort} is not a container port`);
    const metrics = args.find((a) => a.startsWith("--metrics="));
    if (metrics) {
      const metricsPort = Number(metrics.split(":").pop());
      if (!portNumbers.has(metricsPort)) errors.push(`${cname}: --metrics port ${metricsPort} is not a container port`);
      metricsPorts.add(metricsPort);
    }
    c.__ports = ports;
  }
  const annotations = d.spec?.template?.metadata?.annotations ?? {};
  if (annotations["prometheus.io/scrape"] === "true") {
    const port = Number(annotations["prometheus.io/port"]);
    if (!metricsPorts.has(port))
      errors.push(`${name}: prometheus.io/port ${annotations["prometheus.io/port"]} is not a --metrics port`);
  }
  return errors;
}

function crossErrors(docs, serverFlags) {
  const errors = [];
  const deployments = docs.filter((d) => d.kind === "Deployment");
  if (deployments.length !== 1) return [`expected one Deployment, found ${deployments.length}`];
  const d = deployments[0];
  errors.push(...deploymentErrors(d, serverFlags));
  const labels = d.spec?.template?.metadata?.labels;
  const ports = new Map();
  for (const c of d.spec?.template?.spec?.containers ?? []) for (const [k, v] of c.__ports ?? []) ports.set(k, v);
  for (const doc of docs) {
    const name = `${doc.kind}/${doc.metadata?.name}`;
    if (doc.kind === "Service") {
      if (!selects(doc.spec?.selector, labels)) errors.push(`${name}: selector does not select the Deployment's pods`);
      for (const p of doc.spec?.ports ?? []) {
        const t = p.targetPort ?? p.port;
        if (typeof t === "string" ? !ports.has(t) : ![...ports.values()].includes(t))
          errors.push(`${name}: targetPort ${t} is not a container port`);
      }
    } else if (doc.kind === "HorizontalPodAutoscaler") {
      const t = doc.spec?.scaleTargetRef ?? {};
      if (t.apiVersion !== "apps/v1" || t.kind !== "Deployment" || t.name !== d.metadata?.name)
        errors.push(`${name}: scaleTargetRef is not Deployment/${d.metadata?.name}`);
      if ((doc.spec?.minReplicas ?? 1) > doc.spec?.maxReplicas) errors.push(`${name}: minReplicas > maxReplicas`);
    } else if (doc.kind === "PodDisruptionBudget") {
      if (!selects(doc.spec?.selector?.matchLabels, labels)) errors.push(`${name}: selector does not select the Deployment's pods`);
    }
  }
  return errors;
}

function load(dir) {
  const kustomization = YAML.parse(fs.readFileSync(path.join(dir, "kustomization.yaml"), "utf8"));
  const errors = [];
  const listed = kustomization.resources ?? [];
  const onDisk = fs.readdirSync(dir).filter((f) => f.endsWith(".yaml") && f !== "kustomization.yaml");
  for (const f of onDisk) if (!listed.includes(f)) errors.push(`kustomization.yaml: ${f} is not in resources`);
  const docs = [];
  for (const f of listed) {
    if (!fs.existsSync(path.join(dir, f))) { errors.push(`kustomization.yaml: resource ${f} does not exist`); continue; }
    for (const d of YAML.parseAllDocuments(fs.readFileSync(path.join(dir, f), "utf8"))) {
      if (d.errors.length) errors.push(...d.errors.map((e) => `${f}: ${e.message}`));
      else docs.push({ file: f, doc: d.toJS() });
    }
  }
  const images = new Set(docs.flatMap(({ doc }) => (doc.spec?.template?.spec?.containers ?? []).map((c) => c.image)));
  for (const i of kustomization.images ?? []) if (!images.has(i.name)) errors.push(`kustomization.yaml: image ${i.name} is used by no container`);
  return { docs, errors };
}

function check(docs, serverFlags) {
  const errors = [];
  for (const { file, doc } of docs) errors.push(...schemaErrors(doc, `${file}:${doc.kind}/${doc.metadata?.name}`));
  errors.push(...crossErrors(docs.map(({ doc }) => structuredClone(doc)), serverFlags));
  return errors;
}

// Each case breaks one thing; its check must name it.
const SELF_TESTS = [
  ["misspelled field", "deployment.yaml", (d) => { const c = d.spec.template.spec.containers[0]; c.readinesProbe = c.readinessProbe; delete c.readinessProbe; }, "readinesProbe: unknown field"],
  ["unknown top-level spec field", "service.yaml", (d) => { d.spec.selectr = {}; }, "spec.selectr: unknown field"],
  ["wrong type (schema)", "deployment.yaml", (d) => { d.spec.revisionHistoryLimit = "three"; }, "/spec/revisionHistoryLimit: type"],
  ["missing required field (schema)", "hpa.yaml", (d) => { delete d.spec.maxReplicas; }, "required"],
  ["template without labels", "deployment.yaml", (d) => { delete d.spec.template.metadata.labels; }, "pod template has no labels"],
  ["selector not matching the template", "deployment.yaml", (d) => { d.spec.selector.matchLabels["app.kubernetes.io/name"] = "other"; }, "spec.selector does not match"],
  ["Service selecting other pods", "service-headless.yaml", (d) => { d.spec.selector["app.kubernetes.io/component"] = "client"; }, "Service/afmesh-headless: selector does not select"],
  ["Service targetPort not a container port", "service.yaml", (d) => { d.spec.ports[0].targetPort = "grcp"; }, "targetPort grcp is not a container port"],
  ["HPA targeting another Deployment", "hpa.yaml", (d) => { d.spec.scaleTargetRef.name = "afmesh"; }, "scaleTargetRef is not Deployment/afmesh-server"],
  ["PDB selecting other pods", "pdb.yaml", (d) => { d.spec.selector.matchLabels = { app: "afmesh" }; }, "PodDisruptionBudget/afmesh-server: selector does not select"],
  ["flag the server does not have", "deployment.yaml", (d) => { d.spec.template.spec.containers[0].args.push("--metrics-port=9464"); }, "--metrics-port is not an afmesh-server flag"],
  ["metrics on a port the pod does not open", "deployment.yaml", (d) => { const c = d.spec.template.spec.containers[0]; c.args = c.args.map((a) => (a.startsWith("--metrics=") ? "--metrics=0.0.0.0:9465" : a)); }, "--metrics port 9465 is not a container port"],
  ["scrape annotation on another port", "deployment.yaml", (d) => { d.spec.template.metadata.annotations["prometheus.io/port"] = "50051"; }, "prometheus.io/port 50051 is not a --metrics port"],
  ["CPU request not --workers", "deployment.yaml", (d) => { d.spec.template.spec.containers[0].resources.requests.cpu = "1500m"; }, "requests.cpu 1500m is not --workers"],
  ["writable root file system", "deployment.yaml", (d) => { d.spec.template.spec.containers[0].securityContext.readOnlyRootFilesystem = false; }, "readOnlyRootFilesystem is not true"],
  ["probe on a port the pod does not open", "deployment.yaml", (d) => { d.spec.template.spec.containers[0].livenessProbe.grpc.port = 50052; }, "livenessProbe port 50052 is not a container port"],
];

function main() {
  const help = execFileSync(serverBinary, ["--help"], { encoding: "utf8" });
  const serverFlags = new Set(help.match(/--[a-z][a-z0-9-]*/g));
  const { docs, errors: loadErrors } = load(k8sDir);
  const errors = [...loadErrors, ...check(docs, serverFlags)];
  for (const e of errors) console.log(`ERROR ${e}`);
  const kinds = docs.map(({ file, doc }) => `${file}:${doc.kind}/${doc.metadata.name}`);
  if (errors.length) { console.log(`FAILED: ${errors.length} problem(s) in ${kinds.length} objects`); return 1; }
  console.log(`ok: ${kinds.length} objects valid against the Kubernetes 1.33 schemas, no unknown fields, cross-references consistent:`);
  for (const k of kinds) console.log(`  ${k}`);
  if (mode !== "--self-test") return 0;
  let failed = 0;
  for (const [what, file, breakIt, expected] of SELF_TESTS) {
    const broken = docs.map(({ file: f, doc }) => ({ file: f, doc: structuredClone(doc) }));
    breakIt(broken.find((x) => x.file === file).doc);
    const found = check(broken, serverFlags);
    const ok = found.some((e) => e.includes(expected));
    if (!ok) failed++;
    console.log(`${ok ? "ok  " : "MISS"} self-test: ${what}: ${ok ? found.find((e) => e.includes(expected)) : `expected "${expected}", got ${JSON.stringify(found)}`}`);
  }
  console.log(`${SELF_TESTS.length - failed} passed, ${failed} failed (self-tests: each broken manifest caught)`);
  return failed ? 1 : 0;
}

process.exit(main());
