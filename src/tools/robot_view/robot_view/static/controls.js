// The robot view's servo controls (channel "servos" for what the servos have, commands for what
// the page asks): Kp, Ki and Kd of each servo's PID (servo_sim's parameters kp, ki, kd), its
// torque switch (setTorqueEnable / setTorqueDisable) and the appendix 5.3 script's goals, 0 and
// pi/2, with its 3 s flip. The page sends what is typed as it is: the server checks every value
// and answers a refusal with one line, shown under the table.

const FLIP_EVERY = 3000;  // ms, the appendix script's timer
const GAINS = [['kp', 'Kp'], ['ki', 'Ki'], ['kd', 'Kd']];

function goalLabel(goal) {
  return Math.abs(goal - 1.57) < 1e-9 ? 'π/2' : String(goal);
}

export function startControls(socket, view) {
  const body = document.querySelector('#servo-controls tbody');
  const status = document.getElementById('command-status');
  const rows = {};  // servo -> its inputs
  view.servos = null;
  view.commandAnswers = [];  // {name, error} of every answered command, for the tests

  function send(name, args, what) {
    const sent = socket.command(name, args, (error) => {
      view.commandAnswers.push({ name, error });
      status.textContent = error ? `refused: ${error}` : what;
      status.classList.toggle('refused', Boolean(error));
      if (error && name === 'torque') showState();  // the switch goes back to what the servo has
    });
    if (!sent) {
      status.textContent = 'not connected';
      status.classList.add('refused');
    }
  }

  function buildRow(servo, limits) {
    const row = document.createElement('tr');
    row.dataset.servo = servo;
    const cells = [];
    const name = document.createElement('th');
    name.textContent = servo;
    cells.push(name);
    const torque = document.createElement('input');
    torque.type = 'checkbox';
    torque.setAttribute('role', 'switch');
    torque.className = 'torque';
    torque.title = `/olive/servo/${servo}/setTorqueEnable, setTorqueDisable`;
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
      input.addEventListener('keydown', (event) => { if (event.key === 'Enter') setGains(); });
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
      send('set_gains', args, `${servo}: ${GAINS.map(([k, l]) => `${l} ${args[k]}`).join(', ')} set`);
    }
    setButton.addEventListener('click', setGains);
    cells.push(setButton);
    const goalCell = document.createElement('span');
    for (const goal of limits.servos[servo].goals) {
      const button = document.createElement('button');
      button.type = 'button';
      button.className = 'goal';
      button.dataset.goal = String(goal);
      button.textContent = goalLabel(goal);
      button.title = `publish ${goal} on /olive/servo/${servo}/goal/position`;
      button.addEventListener('click', () => send('goal', { servo, position: goal }, `${servo}: goal ${goal} rad`));
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
        send('goal', { servo, position: goal }, `${servo}: goal ${goal} rad (flipping every 3 s)`);
      }, FLIP_EVERY);
    });
    goalCell.append(flipLabel);
    cells.push(goalCell);
    for (const cell of cells) {
      const td = cell.tagName === 'TH' ? cell : document.createElement('td');
      if (td !== cell) td.append(cell);
      row.append(td);
    }
    body.append(row);
    rows[servo] = { torque, gains };
  }

  function showState() {
    if (!view.servos) return;
    for (const [servo, state] of Object.entries(view.servos)) {
      const row = rows[servo];
      if (!row) continue;
      if (state.torque !== null) row.torque.checked = state.torque;
      for (const [key] of GAINS) {
        // never overwrite what the student is typing
        if (state[key] !== null && document.activeElement !== row.gains[key]) row.gains[key].value = String(state[key]);
      }
    }
  }

  socket.subscribe('servos', {}, (message) => {
    if (!Object.keys(rows).length) {
      for (const servo of Object.keys(message.limits.servos)) buildRow(servo, message.limits);
    }
    view.servos = message.state;
    showState();
  }, (line) => { status.textContent = line; status.classList.add('refused'); });
}
