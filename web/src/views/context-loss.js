// Letting go of a lost WebGL context. three.js keeps, for each geometry, texture and render
// target it has drawn, the WebGL objects it made for them, and deletes those on `dispose`; when
// the context is restored it starts its own state afresh but leaves these `dispose` listeners of
// the old state in place, so that a later dispose deletes objects of the lost context ("object
// does not belong to this context"). Disposing them while the context is lost instead runs those
// listeners when every deletion is a silent no-op and removes them; the objects stay usable and
// three.js makes them again in the restored context when they are next drawn.

/** Disposes the geometries of every object under `roots` (scenes or groups). */
export function releaseGeometries(...roots) {
  for (const root of roots) root.traverse((o) => o.geometry?.dispose());
}
