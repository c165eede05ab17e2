// The kit's other pages as links (the robot view, rqt, the windows page, each module's page), those
// that answer now at their default addresses (the server's GET /api/kit-pages looks), refreshed
// every 10 s. A page puts <span id="kit-pages"></span> where the links go and calls showKitPages().
const REFRESH_EVERY = 10_000;  // ms

export function showKitPages(place = document.getElementById('kit-pages')) {
  async function refresh() {
    let pages;
    try {
      const response = await fetch('/api/kit-pages');
      if (!response.ok) return;
      pages = await response.json();
    } catch {
      return;  // this page's server is away: the page says so itself
    }
    const links = pages.flatMap((page, index) => {
      const link = document.createElement('a');
      link.href = page.url;
      link.textContent = page.name;
      link.target = '_blank';
      return index ? [document.createTextNode(' · '), link] : [link];
    });
    place.replaceChildren(...(pages.length ? [document.createTextNode('Other pages: '), ...links] : []));
    place.dataset.pages = String(pages.length);
  }
  refresh();
  setInterval(refresh, REFRESH_EVERY);
}
