// The kit's other pages as links (the robot view, rqt, the windows page, each module's page): those
// that run now (the server's GET api/kit-pages reads the pages folder), refreshed every 10 s. A page
// seen through the front door (its answers carry X-Owl-Mount) links to the others there, relatively,
// so the links work under any path prefix; a page at its own address links to their own addresses.
// A page puts <span id="kit-pages"></span> where the links go and calls showKitPages().
const REFRESH_EVERY = 10_000;  // ms

function link(href, text) {
  const anchor = document.createElement('a');
  anchor.href = href;
  anchor.textContent = text;
  anchor.target = '_blank';
  return anchor;
}

export function showKitPages(place = document.getElementById('kit-pages')) {
  async function refresh() {
    let answer;
    let throughFrontDoor;
    try {
      const response = await fetch('api/kit-pages');
      if (!response.ok) return;
      throughFrontDoor = response.headers.has('X-Owl-Mount');
      answer = await response.json();
    } catch {
      return;  // this page's server is away: the page says so itself
    }
    const links = answer.pages.map((page) => link(throughFrontDoor ? `../${page.mount}/` : page.url, page.name));
    const door = throughFrontDoor ? '../' : answer.front_door;
    if (door) links.push(link(door, 'all pages'));
    const parts = links.flatMap((anchor, index) => (index ? [document.createTextNode(' · '), anchor] : [anchor]));
    place.replaceChildren(...(parts.length ? [document.createTextNode('Other pages: '), ...parts] : []));
    place.dataset.pages = String(answer.pages.length);
  }
  refresh();
  setInterval(refresh, REFRESH_EVERY);
}
