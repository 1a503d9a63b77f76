#!/usr/bin/env node
// An independent export check (docs/architecture.md: "we write the standard extension, chunked, and check it
// with independent readers, since the Khronos validator does not check that extension").
//
//   node check_gltf.mjs FILE [--expect-instances N] [--expect-detail-instances N] [--expect-types K]
//                            [--expect-images N] [--expect-textured-materials N] [--expect-per-mesh JSON]
//                            [--dump-instances OUT.txt]
//   (--dump-instances: every detail instance as a line "mesh x y z qx qy qz qw sx sy sz", its world
//   position and its rotation and scale, sorted, so that two exports can be compared instance for instance
//   with diff, whatever their chunking or the file they came from.)
//   (--expect-per-mesh: {"<mesh name>": copies, ...}, e.g. the statistics' instances_per_look; a mesh the
//    map names with 0 copies may be absent or drawn by no node)
//   (detail instances: copies of meshes that carry collision_spheres extras, i.e. without the terrain)
//
// 1. The Khronos glTF-Validator: any error fails the check (its messages are printed). Warnings are
//    counted and listed in the summary, not fatal.
// 2. glTF-Transform reads the file with every extension it knows registered, so EXT_mesh_gpu_instancing
//    is parsed by a reader that is not ours. Counted:
//      instances        = sum over nodes with the extension of their TRANSLATION count (the ROTATION and
//                         SCALE counts must agree), plus every node with a mesh and no extension (a plain
//                         copy; a terrain node counts as one, since the file draws it once);
//      detail_instances = the same, only for meshes whose extras hold "collision_spheres" (Undergrowth's
//                         detail types, so the terrain is not counted);
//      types            = meshes whose extras hold "collision_spheres".
//    Every instance rotation (extension or node) must be a unit quaternion and every instance value
//    finite.
// 3. Materials (check_materials.mjs): every baseColorTexture read back as a PNG that decodes to the size
//    glTF-Transform reports, repeating, on primitives with TEXCOORD_0, cut-out exactly when alphaMode is
//    MASK; images = distinct images, textured_materials = materials with a baseColorTexture.
// Prints one JSON line: {"file", "errors", "warnings", "warning_codes", "infos", "info_codes",
// "instances", "detail_instances", "instanced_nodes", "plain_nodes", "meshes", "types", "materials",
// "textured_materials", "cutout_materials", "images"}. (The validator
// does not know EXT_mesh_gpu_instancing: expect the infos UNSUPPORTED_EXTENSION, and UNUSED_OBJECT for
// the instance accessors only the extension refers to.) Exit 0 when all checks pass, 1 otherwise (the
// reasons on stderr), 2 on a bad command line.
import { readFile, writeFile } from 'node:fs/promises';
import path from 'node:path';
import process from 'node:process';

import validator from 'gltf-validator';
import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';

import { checkMaterials } from './check_materials.mjs';

const kUnitTolerance = 1e-4;  // float32 quaternions normalized by a writer are within ~1e-7

function usage(message) {
    console.error(`check_gltf: ${message}\nusage: node check_gltf.mjs FILE [--expect-instances N] [--expect-detail-instances N] [--expect-types K] [--expect-images N] [--expect-textured-materials N] [--expect-per-mesh JSON] [--dump-instances OUT.txt]`);
    process.exit(2);
}

function parseArgs(argv) {
    const args = { file: null, expectInstances: null, expectTypes: null, expectDetailInstances: null,
                   expectImages: null, expectTexturedMaterials: null, expectPerMesh: null, dumpInstances: null };
    for (let i = 0; i < argv.length; ++i) {
        const a = argv[i];
        if (a === '--dump-instances') {
            const value = argv[++i];
            if (value === undefined) usage('--dump-instances needs a file name');
            args.dumpInstances = value;
        } else if (a === '--expect-per-mesh') {
            const value = argv[++i];
            let map = null;
            try {
                map = JSON.parse(value ?? '');
            } catch (e) {
                usage(`--expect-per-mesh needs a JSON object: ${e.message}`);
            }
            if (map === null || typeof map !== 'object' || Array.isArray(map) ||
                !Object.values(map).every((n) => Number.isInteger(n) && n >= 0))
                usage('--expect-per-mesh needs a JSON object of non-negative integer counts');
            args.expectPerMesh = map;
        } else if (a === '--expect-instances' || a === '--expect-types' || a === '--expect-detail-instances' ||
            a === '--expect-images' || a === '--expect-textured-materials') {
            const value = argv[++i];
            if (value === undefined || !/^\d+$/.test(value)) usage(`${a} needs a non-negative integer`);
            if (a === '--expect-instances') args.expectInstances = Number(value);
            else if (a === '--expect-detail-instances') args.expectDetailInstances = Number(value);
            else if (a === '--expect-images') args.expectImages = Number(value);
            else if (a === '--expect-textured-materials') args.expectTexturedMaterials = Number(value);
            else args.expectTypes = Number(value);
        } else if (a.startsWith('--')) {
            usage(`unknown option ${a}`);
        } else if (args.file === null) {
            args.file = a;
        } else {
            usage(`more than one file given (${args.file}, ${a})`);
        }
    }
    if (args.file === null) usage('no file given');
    return args;
}

async function validate(file, bytes) {
    const report = await validator.validateBytes(new Uint8Array(bytes), {
        uri: path.basename(file),
        maxIssues: 0,  // unlimited: every error is reported
        writeTimestamp: false,
        // Sidecar buffers and images, resolved next to the file (the exporter embeds, others may not).
        externalResourceFunction: (uri) =>
            readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
    });
    return report.issues;
}

function isUnit(x, y, z, w) {
    return Math.abs(Math.hypot(x, y, z, w) - 1) <= kUnitTolerance;
}

function allFinite(values) {
    for (const v of values) if (!Number.isFinite(v)) return false;
    return true;
}

// The first problem with an instance attribute (non-finite value, non-unit rotation), or null. Float
// accessors are read straight from their array (millions of instances); normalized ones (the extension
// allows byte/short rotations) through getElement, which denormalizes.
function attributeProblem(accessor, semantic) {
    const size = accessor.getElementSize();
    const array = accessor.getArray();
    const direct = !accessor.getNormalized() && array instanceof Float32Array;
    const element = new Array(size);
    for (let i = 0; i < accessor.getCount(); ++i) {
        if (direct) for (let k = 0; k < size; ++k) element[k] = array[i * size + k];
        else accessor.getElement(i, element);
        if (!allFinite(element)) return `${semantic} instance ${i} is not finite`;
        if (semantic === 'ROTATION' && !isUnit(...element))
            return `ROTATION instance ${i} is not a unit quaternion (${element})`;
    }
    return null;
}

function countInstances(document, problems) {
    const root = document.getRoot();
    const detailMeshes = new Set(
        root.listMeshes().filter((m) => Array.isArray((m.getExtras() || {}).collision_spheres)));
    const result = { instances: 0, detail_instances: 0, instanced_nodes: 0, plain_nodes: 0,
                     meshes: root.listMeshes().length, types: detailMeshes.size, per_mesh: {} };
    for (const node of root.listNodes()) {
        const mesh = node.getMesh();
        const instancing = node.getExtension('EXT_mesh_gpu_instancing');
        const name = node.getName() || '(unnamed node)';
        let copies = 0;
        if (instancing) {
            if (!mesh) problems.push(`${name}: EXT_mesh_gpu_instancing on a node without a mesh`);
            const t = instancing.getAttribute('TRANSLATION');
            if (!t) {
                problems.push(`${name}: EXT_mesh_gpu_instancing without TRANSLATION`);
                continue;
            }
            copies = t.getCount();
            for (const semantic of instancing.listSemantics()) {
                const accessor = instancing.getAttribute(semantic);
                if (accessor.getCount() !== copies)
                    problems.push(`${name}: ${semantic} has ${accessor.getCount()} elements, TRANSLATION ${copies}`);
                const problem = attributeProblem(accessor, semantic);
                if (problem) problems.push(`${name}: ${problem}`);
            }
            result.instanced_nodes += 1;
        } else if (mesh) {
            copies = 1;
            const r = node.getRotation();
            if (!allFinite([...node.getTranslation(), ...r, ...node.getScale()]))
                problems.push(`${name}: non-finite translation, rotation or scale`);
            else if (!isUnit(...r)) problems.push(`${name}: rotation is not a unit quaternion (${r})`);
            result.plain_nodes += 1;
        }
        result.instances += copies;
        if (mesh) {
            const meshName = mesh.getName() || '(unnamed mesh)';
            result.per_mesh[meshName] = (result.per_mesh[meshName] ?? 0) + copies;
        }
        if (mesh && detailMeshes.has(mesh)) result.detail_instances += copies;
    }
    return result;
}

// A detail instance as text: the world position (6 decimals) and the instance's own rotation and scale.
function instanceLine(meshName, world, t, r, s) {
    const p = [0, 1, 2].map((k) => world[k] * t[0] + world[4 + k] * t[1] + world[8 + k] * t[2] + world[12 + k]);
    const f = (v) => (Math.abs(v) < 5e-7 ? 0 : v).toFixed(6);
    return [meshName, ...p.map(f), ...r.map(f), ...s.map(f)].join(' ');
}

function dumpInstances(document) {
    const lines = [];
    const detailMeshes = new Set(
        document.getRoot().listMeshes().filter((m) => Array.isArray((m.getExtras() || {}).collision_spheres)));
    for (const node of document.getRoot().listNodes()) {
        const mesh = node.getMesh();
        if (!mesh || !detailMeshes.has(mesh)) continue;
        const world = node.getWorldMatrix();
        const instancing = node.getExtension('EXT_mesh_gpu_instancing');
        const name = mesh.getName() || '(unnamed mesh)';
        if (!instancing) {
            lines.push(instanceLine(name, world, [0, 0, 0], node.getRotation(), node.getScale()));
            continue;
        }
        const get = (semantic, size, fallback) => {
            const a = instancing.getAttribute(semantic);
            return (i) => (a ? a.getElement(i, new Array(size)) : fallback);
        };
        const t = get('TRANSLATION', 3, [0, 0, 0]), r = get('ROTATION', 4, [0, 0, 0, 1]), s = get('SCALE', 3, [1, 1, 1]);
        const n = instancing.getAttribute('TRANSLATION')?.getCount() ?? 0;
        for (let i = 0; i < n; ++i) lines.push(instanceLine(name, world, t(i), r(i), s(i)));
    }
    lines.sort();
    return lines.join('\n') + (lines.length ? '\n' : '');
}

async function main() {
    const args = parseArgs(process.argv.slice(2));
    const file = args.file;
    let bytes;
    try {
        bytes = await readFile(file);
    } catch (e) {
        console.error(`${file}: cannot read: ${e.message}`);
        process.exit(1);
    }

    const problems = [];
    const issues = await validate(file, bytes);
    const codes = (severity) => [...new Set(issues.messages.filter((m) => m.severity === severity).map((m) => m.code))];
    const warningCodes = codes(1);
    if (issues.numErrors > 0) {
        for (const m of issues.messages.filter((m) => m.severity === 0))
            problems.push(`validator error ${m.code} at ${m.pointer ?? m.offset ?? '?'}: ${m.message}`);
    }
    for (const m of issues.messages.filter((m) => m.severity === 1))
        console.error(`${file}: validator warning ${m.code} at ${m.pointer ?? m.offset ?? '?'}: ${m.message}`);

    const io = new NodeIO().registerExtensions(ALL_EXTENSIONS);
    const isGlb = bytes.length >= 4 && bytes.toString('latin1', 0, 4) === 'glTF';
    let counts = null;
    try {
        const document = isGlb ? await io.readBinary(new Uint8Array(bytes)) : await io.read(file);
        counts = countInstances(document, problems);
        if (args.dumpInstances) await writeFile(args.dumpInstances, dumpInstances(document));
        Object.assign(counts, checkMaterials(document, problems));
    } catch (e) {
        problems.push(`glTF-Transform could not read the file: ${e.message}`);
    }

    if (counts && args.expectInstances !== null && counts.instances !== args.expectInstances)
        problems.push(`${counts.instances} instances, expected ${args.expectInstances}`);
    if (counts && args.expectDetailInstances !== null && counts.detail_instances !== args.expectDetailInstances)
        problems.push(`${counts.detail_instances} detail instances, expected ${args.expectDetailInstances}`);
    if (counts && args.expectPerMesh !== null)
        for (const [name, expected] of Object.entries(args.expectPerMesh)) {
            const got = counts.per_mesh[name] ?? 0;
            if (got !== expected) problems.push(`mesh ${name}: ${got} copies, expected ${expected}`);
        }
    if (counts && args.expectTypes !== null && counts.types !== args.expectTypes)
        problems.push(`${counts.types} detail types, expected ${args.expectTypes}`);
    if (counts && args.expectImages !== null && counts.images !== args.expectImages)
        problems.push(`${counts.images} images, expected ${args.expectImages}`);
    if (counts && args.expectTexturedMaterials !== null && counts.textured_materials !== args.expectTexturedMaterials)
        problems.push(`${counts.textured_materials} textured materials, expected ${args.expectTexturedMaterials}`);

    console.log(JSON.stringify({ file: path.basename(file), errors: issues.numErrors, warnings: issues.numWarnings,
                                 warning_codes: warningCodes, infos: issues.numInfos, info_codes: codes(2),
                                 ...(counts ?? {}) }));
    for (const p of problems) console.error(`${file}: ${p}`);
    process.exit(problems.length ? 1 : 0);
}

main().catch((e) => {
    console.error(`check_gltf: ${e.stack || e}`);
    process.exit(1);
});
