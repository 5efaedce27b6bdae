// The README's JavaScript example (node >= 18 or a browser): the npm package `antcd`, built into
// wasm/ by the CMake build. Run by ctest (example_js_quickstart) against wasm/dist.
import createAntcd from 'antcd';

const antcd = await createAntcd();
const torus = antcd.Model.torus(1, 0.25);  // or new antcd.Model(positions, indices)
const ball = antcd.Model.sphere(0.5);
// Poses: column-major rigid 4x4 matrices, as three.js Matrix4.elements; here a translation by x.
const at = (x) => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, 0, 0, 1];

const hit = antcd.collide(torus, at(0), ball, at(1), { allContacts: true });
const pairs = hit.contacts.length / antcd.CONTACT_STRIDE;
console.log(`colliding: ${hit.colliding ? 'yes' : 'no'}, ${pairs} triangle pairs`);

const d = antcd.distance(torus, at(0), ball, at(3));
console.log(`distance at x = 3: ${d.distance.toFixed(6)}`);

torus.delete();  // WebAssembly memory is freed explicitly
ball.delete();
