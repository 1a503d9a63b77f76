#!/usr/bin/env node
// The checker's own test: a check that never fails proves nothing. Writes small files with glTF-Transform
// (an instanced node with unit rotations, the same with a non-unit rotation, a plain node, and a hand-made
// JSON file the validator must reject) and runs check_gltf.mjs on each, expecting its verdict.
import { spawnSync } from 'node:child_process';
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
} finally {
    rmSync(dir, { recursive: true, force: true });
}
if (failures) process.exit(1);
console.log('check_gltf self test: passed');
