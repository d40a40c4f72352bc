// ESLint (flat config): recommended rules for the browser code, the worker, Node scripts and tests.
import js from '@eslint/js';
import globals from 'globals';

export default [
  {
    ignores: ['node_modules/', 'dist/', 'web/pkg/', 'wasm-core/target/', 'e2e/.output/', 'test-results/', 'playwright-report/'],
  },
  js.configs.recommended,
  {
    languageOptions: {
      ecmaVersion: 2023,
      sourceType: 'module',
      globals: { ...globals.browser, ...globals.worker },
    },
    rules: {
      'no-unused-vars': ['error', { argsIgnorePattern: '^_' }],
      eqeqeq: 'error',
      'prefer-const': 'error',
    },
  },
  {
    files: ['scripts/**', 'tests/**', 'e2e/**', '*.config.js', 'web/vite.config.js'],
    languageOptions: { globals: { ...globals.node } },
  },
];
