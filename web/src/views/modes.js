// The views a player shows, the default first: the real-time volume view ('raymarch'), the
// points preview ('points') and the exact march ('exact'); the capture modes of
// docs/FORMATS.md and the values of the <wind-field> element's `view` attribute.
export const VIEWS = ['raymarch', 'points', 'exact'];
