// The robot view's servo controls (channel "servos" for what the servos have, commands for what
// the page asks): Kp, Ki and Kd of each servo's PID (servo_sim's parameters kp, ki, kd), its
// torque switch (setTorqueEnable / setTorqueDisable) and the appendix 5.3 script's goals, 0 and
// pi/2, with its 3 s flip. The page sends what is typed as it is: the server checks every value
// and answers a refusal with one line, shown under the table. Every outcome is what the kit says:
// a goal the servo ignores (torque off) says so, a sent goal is followed in the servo's joint until
// it is reached (or not); a gain field shows the servo's value except while it is being edited
// (marked), and a refused edit stays, marked, until it is corrected or dropped with Escape.

const FLIP_EVERY = 3000;  // ms, the appendix script's timer
const GAINS = [['kp', 'Kp'], ['ki', 'Ki'], ['kd', 'Kd']];
const REACHED = 0.02;  // rad from its goal: the servo is there
const REACH_WITHIN = 5000;  // ms after which a goal not reached is said so
const REFUSAL_STAYS = 5000;  // ms a refusal stays on the status line against a goal's progress
const NUDGE = 0.1;  // rad an arrow of the pad moves a goal
const NUDGE_EVERY = 250;  // ms between nudges while an arrow is held
// [key, label, servo, sign]: left turns the head left (pan +), up looks up (tilt -: + looks down)
const PAD = [['up', '▲', 'tilt', -1], ['left', '◀', 'pan', 1], ['down', '▼', 'tilt', 1], ['right', '▶', 'pan', -1]];

function goalLabel(goal) {
  return Math.abs(goal - 1.57) < 1e-9 ? 'π/2' : String(goal);
}

export function startControls(socket, view) {
  const body = document.querySelector('#servo-controls tbody');
  const status = document.getElementById('command-status');
  const rows = {};  // servo -> its inputs
  view.servos = null;
  view.commandAnswers = [];  // {name, error, result} of every answered command, for the tests
  let following = null;  // {servo, goal, since}: the sent goal whose arrival the status line follows
  const lastGoal = {};  // servo -> the goal this page sent it last

  // A goal's progress (and the flip's goals) does not replace a refusal for REFUSAL_STAYS ms: the
  // line that says what was wrong stays long enough to be read.
  let refusedAt = -Infinity;
  function say(line, refused = false, progress = false) {
    if (progress && performance.now() - refusedAt < REFUSAL_STAYS) return;
    status.textContent = line;
    status.classList.toggle('refused', refused);
    if (refused && !progress) refusedAt = performance.now();
  }

  // onDone(result) when it was carried out. A refusal is said; refused gains stay in their fields,
  // marked, to be corrected (Escape brings the servo's back); other controls show the servo's state.
  function send(name, args, what, onDone = () => say(what)) {
    const sent = socket.command(name, args, (error, result) => {
      view.commandAnswers.push({ name, error, result });
      if (error) {
        say(`refused: ${error}`, true);
        if (name === 'set_gains' && rows[args.servo]) {
          for (const input of Object.values(rows[args.servo].gains)) {
            if (input.classList.contains('edited')) {
              input.classList.add('refused');
              input.title = error;
            }
          }
        } else if (args.servo) {
          showState(args.servo, true);  // back to what the servo has
        }
      } else {
        onDone(result);
      }
    });
    if (!sent) say('not connected: nothing was sent', true);
  }

  function sendGoal(servo, goal, note = '') {
    lastGoal[servo] = goal;
    if (note === '') refusedAt = -Infinity;  // a goal of the user's own: its progress is what they want to see
    send('goal', { servo, position: goal }, '', (result) => {
      const flipping = note !== '';
      if (result && result.outcome === 'ignored') {
        following = null;
        say(`${servo}: goal ${goal} rad ignored: ${result.reason}`, true, flipping);
        return;
      }
      if (result && result.outcome === 'overridden') {
        following = null;
        say(`${servo}: goal ${goal} rad sent, but overridden: ${result.reason}`, true, flipping);
        return;
      }
      following = { servo, goal, since: performance.now(), note };
      followGoal();
    });
  }

  // The status line follows the last sent goal in the joint the kit channel pushes.
  function followGoal() {
    if (!following) return;
    const { servo, goal, since, note } = following;
    const at = view[servo];
    const elapsed = performance.now() - since;
    const where = at === null ? 'no joint state from it' : `at ${at.toFixed(2)} rad`;
    if (at !== null && Math.abs(at - goal) <= REACHED) {
      say(`${servo}: goal ${goal} rad reached in ${(elapsed / 1000).toFixed(1)} s${note}`, false, true);
      following = null;
    } else if (elapsed > REACH_WITHIN) {
      say(`${servo}: goal ${goal} rad not reached after ${REACH_WITHIN / 1000} s (${where})${note}`, true, true);
      following = null;
    } else {
      say(`${servo}: goal ${goal} rad sent, moving (${where})${note}`, false, true);
    }
  }
  view.followGoal = followGoal;  // app.js calls it at each joint update

  function buildRow(servo, limits) {
    const row = document.createElement('tr');
    row.dataset.servo = servo;
    const cells = [];
    row.dataset.module = servo;  // greyed while the servo sends nothing (app.js)
    const name = document.createElement('th');
    const steering = document.createElement('small');
    steering.className = 'steering';
    name.append(servo, steering);
    cells.push(name);
    const torque = document.createElement('input');
    torque.type = 'checkbox';
    torque.setAttribute('role', 'switch');
    torque.className = 'torque';
    torque.title = limits.servos[servo].torque_services.join(', ');
    torque.addEventListener('change', () => send('torque', { servo, enabled: torque.checked },
                                                 `${servo}: torque ${torque.checked ? 'enabled' : 'disabled'}`));
    cells.push(torque);
    const gains = {};
    for (const [key, label] of GAINS) {
      const input = document.createElement('input');
      input.type = 'number';
      input.className = key;
      input.min = '0';
      input.max = String(limits.gains[key]);
      input.step = 'any';
      input.setAttribute('aria-label', `${servo} ${label}`);
      input.addEventListener('input', () => {
        input.classList.add('edited');
        input.classList.remove('refused');
        input.title = '';
      });
      input.addEventListener('keydown', (event) => {
        if (event.key === 'Enter') setGains();
        if (event.key === 'Escape') showState(servo, true);  // drop the edit
      });
      gains[key] = input;
      cells.push(input);
    }
    const setButton = document.createElement('button');
    setButton.type = 'button';
    setButton.className = 'set-gains';
    setButton.textContent = 'Set';
    function setGains() {
      // NaN (an empty or bad field) goes as null: the server names the field in its refusal
      const args = { servo };
      for (const [key] of GAINS) args[key] = gains[key].valueAsNumber;
      send('set_gains', args, '', () => {
        for (const [key] of GAINS) gains[key].classList.remove('edited');
        say(`${servo}: ${GAINS.map(([k, l]) => `${l} ${args[k]}`).join(', ')} set`);
        showState(servo);
      });
    }
    setButton.addEventListener('click', setGains);
    cells.push(setButton);
    // The goals go on a row of their own under the gains: one row of both was 578 px wide, more
    // than a phone's screen and than the panel beside the view at 1280 px.
    const goalCell = document.createElement('span');
    goalCell.className = 'goals';
    goalCell.append('goal (rad) ');
    for (const goal of limits.servos[servo].goals) {
      const button = document.createElement('button');
      button.type = 'button';
      button.className = 'goal';
      button.dataset.goal = String(goal);
      button.textContent = goalLabel(goal);
      button.title = `publish ${goal} on ${limits.servos[servo].goal_topic}`;
      button.addEventListener('click', () => sendGoal(servo, goal));
      goalCell.append(button, ' ');
    }
    const flipLabel = document.createElement('label');
    const flip = document.createElement('input');
    flip.type = 'checkbox';
    flip.className = 'flip';
    flipLabel.append(flip, ' flip every 3 s');
    let flipTimer = null;
    let flipNext = 1;
    flip.addEventListener('change', () => {
      clearInterval(flipTimer);
      flipTimer = null;
      if (!flip.checked) return;
      const goals = limits.servos[servo].goals;
      flipTimer = setInterval(() => {
        const goal = goals[flipNext];
        flipNext = 1 - flipNext;
        sendGoal(servo, goal, ' (flipping every 3 s)');
      }, FLIP_EVERY);
    });
    goalCell.append(flipLabel);
    for (const cell of cells) {
      const td = cell.tagName === 'TH' ? cell : document.createElement('td');
      if (td !== cell) td.append(cell);
      row.append(td);
    }
    const goalRow = document.createElement('tr');
    goalRow.className = 'goal-row';
    goalRow.dataset.servo = servo;
    goalRow.dataset.module = servo;
    const goalTd = document.createElement('td');
    goalTd.colSpan = cells.length - 1;
    goalTd.append(goalCell);
    goalRow.append(document.createElement('td'), goalTd);
    body.append(row, goalRow);
    const controls = [...row.querySelectorAll('input, button'), ...goalRow.querySelectorAll('input, button')];
    rows[servo] = { row, goalRow, torque, gains, steering, controls };
  }

  // The servos' values in their rows; a field being edited keeps the edit unless `only` (a servo's
  // name) is given with `drop`, after a refusal or Escape.
  function showState(only = null, drop = false) {
    if (!view.servos) return;
    for (const [servo, state] of Object.entries(view.servos)) {
      const row = rows[servo];
      if (!row || (only !== null && servo !== only)) continue;
      row.torque.checked = state.torque === true;  // not known (no servo yet): off
      for (const [key] of GAINS) {
        const input = row.gains[key];
        if (drop) {
          input.classList.remove('edited', 'refused');
          input.title = '';
        }
        if (state[key] !== null && !input.classList.contains('edited')) input.value = String(state[key]);
      }
    }
  }

  // Why the servo cannot act on a command now (not running, silent), or null; kit and silent are
  // what app.js shows of the kit channel.
  function unavailable(servo) {
    if (view.kit && !view.kit.modules[servo]) return 'not running';
    const seconds = view.silent && view.silent[servo];
    if (seconds !== undefined && seconds !== null) return `no data for ${seconds} s`;
    return null;
  }

  // Each row's controls work only while its servo runs, and name the other nodes that steer it.
  view.showServoAvailability = () => {
    for (const [servo, { row, goalRow, controls, steering }] of Object.entries(rows)) {
      const why = unavailable(servo);
      for (const control of controls) control.disabled = why !== null;
      row.title = goalRow.title = why === null ? '' : `the ${servo} servo: ${why}; its controls wait for it`;
      const others = view.kit ? view.kit.steered[servo] : [];
      steering.textContent = why !== null ? why : others.length ? `goals also from ${others.join(', ')}` : '';
      steering.classList.toggle('warning', why !== null || others.length > 0);
    }
    for (const arrow of document.querySelectorAll('#servo-pad .arrow')) {
      arrow.disabled = unavailable(arrow.dataset.servo) !== null;
    }
  };

  // An on-screen arrow pad (a phone, a tablet): each arrow nudges a servo's goal by NUDGE from its
  // last goal (or where it is), within its range; held, it repeats.
  function buildPad(limits) {
    const pad = document.getElementById('servo-pad');
    for (const [key, label, servo, sign] of PAD) {
      const button = document.createElement('button');
      button.type = 'button';
      button.className = `arrow ${key}`;
      button.dataset.servo = servo;
      button.textContent = label;
      button.setAttribute('aria-label', `${servo} ${key}`);
      const nudge = () => {
        const [low, high] = limits.servos[servo].range;
        const from = lastGoal[servo] ?? view[servo] ?? 0;
        const goal = Math.min(high, Math.max(low, Math.round((from + sign * NUDGE) * 1000) / 1000));
        lastGoal[servo] = goal;
        sendGoal(servo, goal);
      };
      let repeat = null;
      const stop = () => { clearInterval(repeat); repeat = null; button.classList.remove('held'); };
      button.addEventListener('pointerdown', (event) => {
        event.preventDefault();
        button.setPointerCapture(event.pointerId);
        button.classList.add('held');
        nudge();
        clearInterval(repeat);
        repeat = setInterval(nudge, NUDGE_EVERY);
      });
      for (const end of ['pointerup', 'pointercancel', 'lostpointercapture']) button.addEventListener(end, stop);
      pad.append(button);
    }
  }

  socket.subscribe('servos', {}, (message) => {
    if (!Object.keys(rows).length) {
      for (const servo of Object.keys(message.limits.servos)) buildRow(servo, message.limits);
      buildPad(message.limits);
    }
    view.servos = message.state;
    showState();
    view.showServoAvailability();
  }, (line) => { status.textContent = line; status.classList.add('refused'); });
}
