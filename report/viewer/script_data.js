// Data a page opened from the file system cannot fetch (file:// forbids it) comes as small classic
// scripts, each calling a global callback with its file's name and the data. A loader adds one
// script per file on first use, keeps the decoded result, and resolves null when the script fails.
export function scriptLoader(callbackName, decode) {
  const loaded = new Map(); // file -> Promise<decoded | null>
  const waiting = new Map(); // file -> resolve(arguments after the file)
  window[callbackName] = (file, ...data) => {
    const resolve = waiting.get(file);
    if (!resolve) return;
    waiting.delete(file);
    resolve(data);
  };
  return (file, scriptPath) => {
    if (!scriptPath) return Promise.resolve(null);
    if (!loaded.has(file)) {
      loaded.set(
        file,
        new Promise((resolve) => {
          waiting.set(file, resolve);
          const script = document.createElement('script');
          script.src = scriptPath;
          script.onerror = () => resolve(null);
          document.head.appendChild(script);
        }).then((data) => (data ? decode(...data) : null)),
      );
    }
    return loaded.get(file);
  };
}
