#!/usr/bin/env node
// The checker's own test: a check that never fails proves nothing. Writes small files with glTF-Transform
// (an instanced node with unit rotations, the same with a non-unit rotation, a plain node, and a hand-made
// JSON file the validator must reject, and textured materials right and wrong) and runs check_gltf.mjs on
// each, expecting its verdict.
import { spawnSync } from 'node:child_process';
import zlib from 'node:zlib';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import process from 'node:process';
import { fileURLToPath } from 'node:url';

import { Document, NodeIO } from '@gltf-transform/core';
import { EXTMeshGPUInstancing } from '@gltf-transform/extensions';

const here = path.dirname(fileURLToPath(import.meta.url));
const checker = path.join(here, 'check_gltf.mjs');

async function writeInstanced(file, rotations) {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const vec3 = (values) => doc.createAccessor().setType('VEC3').setArray(new Float32Array(values)).setBuffer(buffer);
    const prim = doc.createPrimitive().setAttribute('POSITION', vec3([0, 0, 0, 1, 0, 0, 0, 1, 0]));
    const mesh = doc.createMesh('triangle').addPrimitive(prim).setExtras({ collision_spheres: [[0, 0, 0, 1]] });
    const ext = doc.createExtension(EXTMeshGPUInstancing);
    const count = rotations.length / 4;
    const instanced = ext.createInstancedMesh()
        .setAttribute('TRANSLATION', vec3(Array.from({ length: count * 3 }, (_, i) => i)))
        .setAttribute('ROTATION', doc.createAccessor().setType('VEC4').setArray(new Float32Array(rotations)).setBuffer(buffer))
        .setAttribute('SCALE', vec3(new Array(count * 3).fill(1)));
    const scene = doc.createScene();
    scene.addChild(doc.createNode('instanced').setMesh(mesh).setExtension('EXT_mesh_gpu_instancing', instanced));
    scene.addChild(doc.createNode('plain').setMesh(mesh).setTranslation([5, 0, 0]));
    await new NodeIO().registerExtensions([EXTMeshGPUInstancing]).write(file, doc);
}

// A w x h RGBA PNG, every row with filter 0 (the checker's decoder is the other side of this).
function crc32(bytes) {
    let c = ~0;
    for (const b of bytes) {
        c ^= b;
        for (let k = 0; k < 8; ++k) c = (c >>> 1) ^ (0xedb88320 & -(c & 1));
    }
    return ~c >>> 0;
}
function chunk(type, data) {
    const head = Buffer.alloc(8);
    head.writeUInt32BE(data.length, 0);
    head.write(type, 4, 'latin1');
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(crc32(Buffer.concat([head.subarray(4), data])), 0);
    return Buffer.concat([head, data, crc]);
}
function pngBytes(w, h, alpha) {
    const ihdr = Buffer.alloc(13);
    ihdr.writeUInt32BE(w, 0);
    ihdr.writeUInt32BE(h, 4);
    ihdr[8] = 8;
    ihdr[9] = 6;
    const raw = Buffer.alloc(h * (1 + w * 4), 200);
    for (let y = 0; y < h; ++y) {
        raw[y * (1 + w * 4)] = 0;
        for (let x = 0; x < w; ++x) raw[y * (1 + w * 4) + 1 + x * 4 + 3] = alpha(x, y);
    }
    return new Uint8Array(Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
                                         chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]));
}

async function writeTextured(file, { uv, mask, holes }) {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const acc = (type, values) => doc.createAccessor().setType(type).setArray(new Float32Array(values)).setBuffer(buffer);
    const texture = doc.createTexture('t').setMimeType('image/png')
        .setImage(pngBytes(8, 4, (x, y) => (holes && x === y ? 0 : 255)));
    const material = doc.createMaterial('m').setBaseColorTexture(texture).setAlphaMode(mask ? 'MASK' : 'OPAQUE');
    material.getBaseColorTextureInfo().setWrapS(10497).setWrapT(10497);
    const prim = doc.createPrimitive().setMaterial(material)
        .setAttribute('POSITION', acc('VEC3', [0, 0, 0, 1, 0, 0, 0, 1, 0]));
    if (uv) prim.setAttribute('TEXCOORD_0', acc('VEC2', [0, 0, 1, 0, 0, 1]));
    doc.createScene().addChild(doc.createNode('n').setMesh(doc.createMesh('textured').addPrimitive(prim)));
    await new NodeIO().write(file, doc);
}

function check(file, args) {
    const run = spawnSync(process.execPath, [checker, file, ...args], { encoding: 'utf8' });
    return { status: run.status, out: run.stdout + run.stderr };
}

const dir = mkdtempSync(path.join(os.tmpdir(), 'ug-gltf-self-test-'));
let failures = 0;
function expect(what, result, status, text) {
    if (result.status !== status || (text && !result.out.includes(text))) {
        console.error(`self test: ${what}: expected exit ${status}${text ? ` mentioning '${text}'` : ''}, got ` +
                      `${result.status}:\n${result.out}`);
        ++failures;
    }
}

try {
    const good = path.join(dir, 'good.glb');
    await writeInstanced(good, [0, 0, 0, 1, 0, 0.6, 0, 0.8, 0, 0, 0, 1]);
    expect('good file, right count', check(good, ['--expect-instances', '4', '--expect-types', '1']), 0,
           '"instances":4');
    expect('good file, wrong count', check(good, ['--expect-instances', '5']), 1, 'expected 5');
    expect('good file, wrong type count', check(good, ['--expect-types', '2']), 1, 'expected 2');
    expect('good file, right copies per mesh', check(good, ['--expect-per-mesh', '{"triangle": 4, "absent": 0}']), 0, '');
    expect('good file, wrong copies per mesh', check(good, ['--expect-per-mesh', '{"triangle": 3}']), 1,
           'mesh triangle: 4 copies, expected 3');
    expect('good file, a mesh it lacks', check(good, ['--expect-per-mesh', '{"other": 1}']), 1,
           'mesh other: 0 copies, expected 1');

    const bad_rotation = path.join(dir, 'bad_rotation.gltf');
    await writeInstanced(bad_rotation, [0, 0, 0, 1, 0, 0, 0, 2]);
    expect('non-unit instance rotation', check(bad_rotation, []), 1, 'not a unit quaternion');

    const invalid = path.join(dir, 'invalid.gltf');
    writeFileSync(invalid, JSON.stringify({
        asset: { version: '2.0' },
        accessors: [{ bufferView: 7, componentType: 5126, count: 3, type: 'VEC3' }],
    }));
    expect('validator error', check(invalid, []), 1, 'validator error');

    expect('missing file', check(path.join(dir, 'missing.glb'), []), 1, 'cannot read');

    const textured = path.join(dir, 'textured.glb');
    await writeTextured(textured, { uv: true, mask: true, holes: true });
    expect('textured material', check(textured, ['--expect-images', '1', '--expect-textured-materials', '1']), 0,
           '"textured_materials":1');
    expect('textured material, wrong image count', check(textured, ['--expect-images', '2']), 1, 'expected 2');
    const no_uv = path.join(dir, 'no_uv.glb');
    await writeTextured(no_uv, { uv: false, mask: false, holes: false });
    expect('texture without TEXCOORD_0', check(no_uv, []), 1, 'without TEXCOORD_0');
    const opaque_holes = path.join(dir, 'opaque_holes.glb');
    await writeTextured(opaque_holes, { uv: true, mask: false, holes: true });
    expect('cut-out texture drawn opaque', check(opaque_holes, []), 1, 'has cut-out pixels');
} finally {
    rmSync(dir, { recursive: true, force: true });
}
if (failures) process.exit(1);
console.log('check_gltf self test: passed');
