// Builds the page: the felt.v1 messages generated from protocol/felt/v1 (protoc with
// protoc-gen-es) into a folder of generated code, then one bundle with three.js (esbuild) into
// the folder feltd serves. The page imports the generated modules as felt-proto/felt/v1/*.
//   node build.mjs [--out DIR] [--gen DIR] [--protoc PROTOC]

import { execFileSync } from "node:child_process";
import { copyFileSync, mkdirSync, readdirSync, rmSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import * as esbuild from "esbuild";

const here = dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const option = (name, fallback) => {
  const at = args.indexOf(name);
  return at >= 0 ? args[at + 1] : fallback;
};
const out = resolve(option("--out", join(here, "dist")));
const protoc = option("--protoc", "protoc");
const protocol = resolve(here, "..", "protocol");
const generated = resolve(option("--gen", join(here, "gen")));

rmSync(generated, { recursive: true, force: true });
mkdirSync(generated, { recursive: true });
const protos = readdirSync(join(protocol, "felt", "v1")).filter((f) => f.endsWith(".proto"))
  .map((f) => join("felt", "v1", f));
execFileSync(protoc, [
  `--plugin=protoc-gen-es=${join(here, "node_modules", ".bin", "protoc-gen-es")}`,
  `--es_out=${generated}`, "--es_opt=target=js,import_extension=js", `-I${protocol}`, ...protos,
], { cwd: protocol, stdio: "inherit" });

mkdirSync(out, { recursive: true });
await esbuild.build({
  entryPoints: [join(here, "src", "main.js")],
  bundle: true,
  format: "esm",
  target: "es2022",
  minify: true,
  sourcemap: true,
  outfile: join(out, "app.js"),
  logLevel: "warning",
  alias: { "felt-proto": generated },
  // the generated code imports @bufbuild/protobuf from outside web/
  nodePaths: [join(here, "node_modules")],
});
for (const file of ["index.html", "style.css"]) copyFileSync(join(here, "src", file), join(out, file));
console.log(`page built into ${out}`);
